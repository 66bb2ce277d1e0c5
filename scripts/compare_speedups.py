#!/usr/bin/python3
"""Repeatability of two sweeps of the same definition: the share of rows whose speedups agree.

For every configuration that is ok in both results files (naive's own rows left out: their
speedup is 1 by definition), the relative difference |a - b| / min(a, b) of the two speedups;
prints the share within 5% and within 10%, the median and worst difference, naive's median
render time in each run per scene, and (with --cpu) the same for speedups formed from CPU time.

Usage: scripts/compare_speedups.py A.json B.json [--cpu]
"""

import argparse
import json
import statistics
import sys


def load(path):
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    if not isinstance(doc, dict) or doc.get("format") != "accelbench-results":
        raise SystemExit(f"compare_speedups: {path}: /format: not an accelbench results file")
    return doc


def speedups(doc, cpu):
    """key -> speedup of every ok non-naive row (wall, or CPU time with cpu=True)."""
    naive_cpu = {}
    if cpu:
        for r in doc["rows"]:
            if r.get("structure") == "naive" and r.get("status") == "ok" and "cpu_ms" in r:
                naive_cpu[(r["scene"], json.dumps(r.get("integrator_params", {}), sort_keys=True))] = \
                    r["cpu_ms"]["median"]
    out = {}
    for r in doc["rows"]:
        if r.get("status") != "ok" or r.get("structure") == "naive":
            continue
        if cpu:
            ref = naive_cpu.get((r["scene"], json.dumps(r.get("integrator_params", {}), sort_keys=True)))
            if ref and r.get("cpu_ms", {}).get("median", 0) > 0:
                out[r["key"]] = ref / r["cpu_ms"]["median"]
        elif r.get("speedup", 0) > 0:
            out[r["key"]] = r["speedup"]
    return out


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--cpu", action="store_true", help="also compare speedups formed from CPU time")
    args = parser.parse_args(argv)
    a, b = load(args.a), load(args.b)
    if a["sweep"] != b["sweep"]:
        print("compare_speedups: the two files are of different sweep definitions", file=sys.stderr)
        return 1
    for label, cpu in [("wall-clock speedups", False)] + ([("CPU-time speedups", True)] if args.cpu else []):
        sa, sb = speedups(a, cpu), speedups(b, cpu)
        common = sorted(set(sa) & set(sb))
        if not common:
            print(f"{label}: no row is ok in both files")
            continue
        diff = [abs(sa[k] - sb[k]) / min(sa[k], sb[k]) for k in common]
        within5 = sum(d <= 0.05 for d in diff) / len(diff)
        within10 = sum(d <= 0.10 for d in diff) / len(diff)
        print(f"{label}: {len(common)} rows; within 5%: {100 * within5:.1f}%; within 10%: {100 * within10:.1f}%; "
              f"median difference {100 * statistics.median(diff):.1f}%, worst {100 * max(diff):.1f}%")
    for doc, path in ((a, args.a), (b, args.b)):
        naive = {r["scene"]: r["render_ms"]["median"] for r in doc["rows"]
                 if r.get("structure") == "naive" and r.get("status") == "ok" and not r.get("integrator_params")}
        noisy = sum(1 for r in doc["rows"] if r.get("noisy"))
        print(f"{path}: naive median ms {json.dumps({k: round(v, 1) for k, v in naive.items()})}; "
              f"noisy rows {noisy}; wall {sum(run.get('wall_s', 0) for run in doc.get('runs', [])):.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
