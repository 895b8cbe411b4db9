#!/usr/bin/env python3
"""Compare every registered structure on one scene through `rtlab trace`.

Generates the scene (a sphere flake by default) and fixed ray sets (primary, shadow, diffuse), so
every structure traces the same rays; runs each structure with --repeat K (median) and a separate
--stats pass; prints a Markdown table (build ms, Mrays/s per ray kind, nodes/ray, prims/ray,
bytes/prim) with the command, git revision, compiler and CPU, and optionally writes JSON.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile


def run(cmd):
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit(f"compare_structures: {' '.join(cmd)} failed: {res.stderr.strip()}")
    return res.stdout


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def git_rev(root):
    try:
        return subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True).stdout.strip() or "unknown"
    except OSError:
        return "unknown"


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rtlab", default="build/release/apps/rtlab", help="rtlab executable")
    ap.add_argument("--gen", default="flake", help="generator name (default flake)")
    ap.add_argument("--size", type=int, default=3, help="generator --size (default 3)")
    ap.add_argument("--as", dest="as_", default="mesh", choices=["mesh", "spheres"],
                    help="tessellated mesh or analytic primitives (default mesh)")
    ap.add_argument("--tess", default="uv:16x8", help="tessellation for --as mesh")
    ap.add_argument("--count", type=int, default=100000, help="rays per kind (default 100000)")
    ap.add_argument("--repeat", type=int, default=3, help="timed runs per case, median (3)")
    ap.add_argument("--threads", type=int, default=0, help="worker threads (default: all)")
    ap.add_argument("--accel", action="append", default=[],
                    help="structure spec, e.g. 'bvh:binned,max_leaf=8' (repeatable; default: every "
                         "registered structure but brute, with default parameters)")
    ap.add_argument("--json", help="also write the raw rows as JSON here")
    ap.add_argument("--markdown", help="also write the table as Markdown here")
    args = ap.parse_args()

    rtlab = args.rtlab
    if not os.path.exists(rtlab):
        sys.exit(f"compare_structures: {rtlab} not found (build the release preset first)")
    listing = json.loads(run([rtlab, "list", "--json"]))
    accels = args.accel or [s["default_spec"] for s in listing["structures"]
                            if s["name"] != "brute"]

    kinds = ["primary", "shadow", "diffuse"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        # A JSON scene keeps the generator's camera and lights (the SPD view for the flake).
        scene = os.path.join(tmp, "scene.json")
        gen = [rtlab, "gen", args.gen, "--size", str(args.size), "--as", args.as_, "-o", scene]
        if args.as_ == "mesh":
            gen += ["--tess", args.tess]
        subprocess.run(gen, check=True, capture_output=True)
        info = json.loads(run([rtlab, "info", scene, "--json"]))
        for kind in kinds:
            run([rtlab, "rays", "--scene", scene, "--kind", kind, "--count", str(args.count),
                 "--seed", "1", "-o", os.path.join(tmp, kind + ".rays")])
        for accel in accels:
            row = {"kinds": {}}
            for kind in kinds:
                cmd = [rtlab, "trace", "--scene", scene, "--rays", os.path.join(tmp, kind + ".rays"),
                       "--accel", accel, "--repeat", str(args.repeat), "--stats"]
                if args.threads:
                    cmd += ["--threads", str(args.threads)]
                if kind == "shadow":
                    cmd.append("--any-hit")
                out = json.loads(run(cmd))
                row["kinds"][kind] = out
                row["accel"] = out["accel"]  # the canonical spec rtlab trace ran
                row["build_ms"] = out["build_ms"]
                row["bytes_per_prim"] = out["bytes_per_prim"]
            rows.append(row)
            print(f"  {accel} done", file=sys.stderr)

    prims = info.get("primitives", "?")
    title = (f"{args.gen} --size {args.size} --as {args.as_}"
             + (f" --tess {args.tess}" if args.as_ == "mesh" else "") + f", {prims} primitives")
    lines = [f"Scene: {title}; {args.count} rays per kind, median of {args.repeat} runs, "
             f"threads: {args.threads or 'all'}.", "",
             "| structure | build ms | Mrays/s primary | Mrays/s shadow | Mrays/s diffuse "
             "| nodes/ray primary | prims/ray primary | nodes/ray diffuse | prims/ray diffuse "
             "| bytes/prim |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        k = r["kinds"]
        lines.append(
            f"| {r['accel']} | {r['build_ms']:.1f} | {k['primary']['mrays_per_s']:.2f} "
            f"| {k['shadow']['mrays_per_s']:.2f} | {k['diffuse']['mrays_per_s']:.2f} "
            f"| {k['primary']['nodes_per_ray']:.1f} | {k['primary']['prims_per_ray']:.1f} "
            f"| {k['diffuse']['nodes_per_ray']:.1f} | {k['diffuse']['prims_per_ray']:.1f} "
            f"| {r['bytes_per_prim']:.1f} |")
    cc = run([rtlab, "--version"]).strip()
    lines += ["", f"Command: `bench/compare_structures.py {' '.join(sys.argv[1:])}`; "
              f"git {git_rev(os.path.dirname(os.path.abspath(__file__)))}; {cc}; "
              f"CPU: {cpu_name()} ({os.cpu_count()} cores)."]
    table = "\n".join(lines)
    print(table)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(table + "\n")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"scene": title, "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()
