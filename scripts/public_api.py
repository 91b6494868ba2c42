#!/usr/bin/env python3
"""Counts the core crate's public API from rustdoc's JSON: every item a user can name, reached
from the crate root through public modules and re-exports, plus the public methods, associated
constants and fields of those types' inherent impls and the items of the crate's own traits.
Each item counts once however many paths reach it. Pass --list to print them by path.

Usage:
  cargo +nightly rustdoc -p meshq --all-features --lib -- -Z unstable-options --output-format json
  python3 scripts/public_api.py [target/doc/meshq.json] [--list]
"""
import collections
import json
import sys

args = [a for a in sys.argv[1:] if not a.startswith("--")]
listing = "--list" in sys.argv
data = json.load(open(args[0] if args else "target/doc/meshq.json"))
index = data["index"]
seen = {}
counts = collections.Counter()


def kind_of(item):
    return next(iter(item["inner"])) if isinstance(item["inner"], dict) else item["inner"]


def visit(item_id, path):
    item = index.get(str(item_id))
    if item is None or item.get("crate_id", 0) != 0:
        return
    kind = kind_of(item)
    inner = item["inner"][kind]
    if kind == "use":
        if inner.get("id") is not None:
            if inner.get("is_glob"):
                target = index.get(str(inner["id"]))
                if target and kind_of(target) == "module":
                    for child in target["inner"]["module"]["items"]:
                        visit(child, path)
                return
            visit(inner["id"], path[:-1] + [inner["name"]])
        return
    if item["visibility"] != "public" and kind not in ("variant", "struct_field"):
        return
    if item_id in seen:
        return
    seen[item_id] = "::".join(path)
    counts[kind] += 1
    if kind == "module":
        for child in inner["items"]:
            child_item = index.get(str(child))
            name = child_item.get("name") if child_item else None
            visit(child, path + [name or "?"])
    elif kind in ("struct", "enum", "union"):
        for impl_id in inner.get("impls", []):
            impl = index.get(str(impl_id))
            if impl is None:
                continue
            body = impl["inner"]["impl"]
            if body.get("trait") is not None or body.get("blanket_impl") is not None:
                continue
            for member in body["items"]:
                m = index.get(str(member))
                if m is not None and m["visibility"] == "public":
                    visit(member, path + [m["name"]])
        if kind == "struct":
            fields = inner["kind"].get("plain", {}).get("fields", []) if isinstance(inner["kind"], dict) else []
            for f in fields:
                fi = index.get(str(f))
                if fi is not None and fi["visibility"] == "public":
                    seen.setdefault(f, "::".join(path + [fi["name"]]))
                    counts["field"] += 1
    elif kind == "trait":
        for member in inner["items"]:
            m = index.get(str(member))
            if m is not None:
                seen.setdefault(member, "::".join(path + [m["name"]]))
                counts["trait_" + kind_of(m)] += 1


visit(data["root"], [index[str(data["root"])]["name"]])
for kind, n in sorted(counts.items()):
    print(f"{kind:20} {n:5}")
print(f"{'total':20} {sum(counts.values()):5}")
advanced = sum(1 for p in seen.values() if p.split("::")[1:2] == ["advanced"])
print(f"{'of which advanced':20} {advanced:5}")
print(f"{'outside advanced':20} {len(seen) - advanced:5}")
if listing:
    for path in sorted(seen.values()):
        print(path)
