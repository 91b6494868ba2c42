#!/usr/bin/env python3
"""Counts the public items of the core crate as rustdoc lists them (target/doc/meshq/all.html,
after `cargo doc -p meshq --all-features --no-deps`), by kind, plus the public functions and
methods: the measure of how much a reader of the API has to take in.

Usage: python3 scripts/public_items.py [path/to/doc/meshq]
"""
import html
import pathlib
import re
import sys

doc = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "target/doc/meshq")
text = (doc / "all.html").read_text()
sections = re.findall(r'<h3 id="([a-z-]+)">[^<]*</h3><ul class="all-items">(.*?)</ul>', text, re.S)
total = 0
for kind, items in sections:
    n = items.count("<li>")
    total += n
    print(f"{kind:16} {n:5}")
print(f"{'items':16} {total:5}")
# Methods and associated items on the public types' own pages (inherent and trait impls
# written in this crate), each counted once per page.
# What derives and blanket impls add to every type: not this crate's API.
STANDARD = set(
    "clone clone_from clone_into clone_to_uninit fmt eq ne default hash hash_slice cmp "
    "partial_cmp lt le gt ge max min clamp from into try_from try_into borrow borrow_mut "
    "type_id to_owned to_string vzip source description cause provide deref deref_mut drop "
    "serialize deserialize".split()
)
methods = 0
for page in doc.rglob("*.html"):
    name = page.name
    if not (name.startswith("struct.") or name.startswith("enum.") or name.startswith("trait.")):
        continue
    body = page.read_text()
    found = set(re.findall(r'id="(?:method|tymethod|associatedconstant)\.([A-Za-z_0-9]+)"', body))
    methods += len(found - STANDARD)
print(f"{'methods':16} {methods:5}")
