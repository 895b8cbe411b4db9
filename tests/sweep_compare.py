#!/usr/bin/env python3
"""Compares two merged sweep tables (rtlab sweep merge ... -o T: T.json) case for case, ignoring
timings and provenance. Usage: sweep_compare.py A.json B.json [--failed N] [--total N]
Exit 0 when they agree (and, with --failed/--total, hold that many failed and total cases)."""
import json
import sys

IGNORED = {"build_ms", "trace_ms", "trace_ms_runs", "mrays_per_s", "render_ms", "ns_per_test",
           "setup_ns_per_ray", "provenance", "shard"}


def main():
    args = sys.argv[1:]
    want_failed = int(args[args.index("--failed") + 1]) if "--failed" in args else None
    want_total = int(args[args.index("--total") + 1]) if "--total" in args else None
    a, b = (json.load(open(p)) for p in args[:2])
    problems = []
    for name, t in (("A", a), ("B", b)):
        if t["missing"]:
            problems.append(f"{name}: {len(t['missing'])} cases missing")
        if want_total is not None and len(t["cases"]) != want_total:
            problems.append(f"{name}: {len(t['cases'])} cases, expected {want_total}")
        failed = sum(1 for c in t["cases"] if c["status"] != "done")
        if want_failed is not None and failed != want_failed:
            problems.append(f"{name}: {failed} failed cases, expected {want_failed}")
    if len(a["cases"]) != len(b["cases"]):
        problems.append(f"{len(a['cases'])} cases against {len(b['cases'])}")
    for ca, cb in zip(a["cases"], b["cases"]):
        ka = {k: v for k, v in ca.items() if k not in IGNORED}
        kb = {k: v for k, v in cb.items() if k not in IGNORED}
        if ka != kb:
            diff = sorted(k for k in set(ka) | set(kb) if ka.get(k) != kb.get(k))
            problems.append(f"case {ca['case']} differs in {diff}: "
                            f"{[ka.get(k) for k in diff]} vs {[kb.get(k) for k in diff]}")
    for p in problems[:20]:
        print("sweep_compare:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
