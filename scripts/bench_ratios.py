#!/usr/bin/env python3
"""Prints meshq-versus-peer ratios from criterion's JSON output (target/criterion).

Run `cargo bench -p meshq-bench` first. For every benchmark group it lists each entry's mean
time, then the ratio of each meshq entry against each peer entry of the same group, as
throughput ratios (peer time / meshq time: above 1 means meshq is faster). With --json it
prints the same as one JSON object so runs can be compared.
"""
import json
import pathlib
import sys

root = pathlib.Path(__file__).resolve().parent.parent / "target" / "criterion"
if not root.is_dir():
    sys.exit("no target/criterion: run `cargo bench -p meshq-bench` first")

report = {}
for group in sorted(p for p in root.iterdir() if p.is_dir() and p.name != "report"):
    means = {}
    for bench in sorted(p for p in group.iterdir() if p.is_dir() and p.name != "report"):
        estimates = bench / "new" / "estimates.json"
        if estimates.is_file():
            means[bench.name] = json.loads(estimates.read_text())["mean"]["point_estimate"]
    ours = {k: v for k, v in means.items() if k.startswith("meshq")}
    peers = {k: v for k, v in means.items() if not k.startswith("meshq")}
    report[group.name] = {
        "mean_ms": {k: v / 1e6 for k, v in means.items()},
        "ratios": {f"{m} vs {p}": pv / mv for m, mv in ours.items() for p, pv in peers.items()},
    }

if "--json" in sys.argv:
    print(json.dumps(report, indent=2))
else:
    for group, data in report.items():
        print(f"{group}")
        for name, ms in data["mean_ms"].items():
            print(f"  {name:32} {ms:10.2f} ms")
        for pair, ratio in data["ratios"].items():
            print(f"  {pair:52} {ratio:6.2f}x")
