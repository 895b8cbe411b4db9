#!/usr/bin/env python3
"""The kd-tree table from `rtlab_bench --suite kdtree` JSON (bench/kdtree_bench.cpp).

Prints Markdown: per scene and ray kind, Mrays/s, nodes/ray and prims/ray of every contender with
the kd-tree rows' ratio to the best binary BVH; then build times with the kd-tree rows' ratio to
bvh:binned. Usage:
  build/release/bench/rtlab_bench --suite kdtree --benchmark_out=kd.json \\
      --benchmark_out_format=json
  python3 bench/report_kdtree.py kd.json >> table.md
"""
import argparse
import json
import sys


def short(spec):
    """The spec without parameters at their default (the bench's canonical specs list all)."""
    keep = {"perfect", "from", "traversal", "leaves"}
    name, *params = spec.split(",")
    shown = [p for p in params if p.split("=")[0] in keep]
    return ",".join([name] + shown)


def split_counters(bench):
    per = {}
    for key, value in bench.items():
        if "|" in key:
            spec, what = key.rsplit("|", 1)
            per.setdefault(spec, {})[what] = value
    return per


def main():
    parser = argparse.ArgumentParser(
        description="The kd-tree table (Markdown, on stdout) from rtlab_bench --suite "
        "kdtree JSON output.")
    parser.add_argument("json", help="the --benchmark_out file of rtlab_bench --suite kdtree")
    args = parser.parse_args()
    try:
        with open(args.json) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"report_kdtree.py: {args.json}: {e}")
    if not isinstance(data, dict) or not isinstance(data.get("benchmarks"), list):
        sys.exit(f"report_kdtree.py: {args.json}: no 'benchmarks' list (not rtlab_bench JSON)")
    trace = [b for b in data["benchmarks"] if b["name"].startswith("kdtree/trace/")]
    build = [b for b in data["benchmarks"] if b["name"].startswith("kdtree/build/")]
    if trace:
        print("| scene | rays | structure | Mrays/s | nodes/ray | prims/ray | kd / best BVH |")
        print("|---|---|---|---:|---:|---:|---:|")
        for b in trace:
            _, _, scene, kind = b["name"].split("/")[:4]
            for spec, c in split_counters(b).items():
                ratio = f"{c['ratio']:.2f}x" if "ratio" in c else ""
                print(f"| {scene} | {kind} | {short(spec)} | {c['Mrays/s']:.3f} | "
                      f"{c['nodes/ray']:.1f} | {c['prims/ray']:.2f} | {ratio} |")
    if build:
        print()
        print("| scene | threads | structure | build ms | refs/prim | SAH cost | kd / bvh:binned |")
        print("|---|---|---|---:|---:|---:|---:|")
        for b in build:
            _, _, scene, threads = b["name"].split("/")[:4]
            for spec, c in split_counters(b).items():
                ratio = f"{c['build_ratio']:.2f}x" if "build_ratio" in c else ""
                print(f"| {scene} | {threads.split(':')[1]} | {short(spec)} | "
                      f"{c['build_ms']:.0f} | {c['refs/prim']:.2f} | {c['sah_cost']:.2f} | "
                      f"{ratio} |")


if __name__ == "__main__":
    main()
