"""The grid2 block (two-level grid and cost model) from `rtlab trace` runs instead of rtlab_bench
(for a machine where the benchmark executable is not built): generates the scenes and ray sets,
runs `rtlab trace --threads 1 --stats` for every structure, scene and ray kind, interleaved over
--rounds rounds (one process per run; Mrays/s is the median over the rounds), and writes the
same block and plot as `report.py --suite grid2` (bench/report_grid2.py). Build rows come from
the trace runs' build_ms (one thread, with the tracer's clip callback); there are no 2-thread
build rows.

Usage: python3 bench/grid2_trace_table.py [--rtlab build/release/apps/rtlab] [--rounds 3]
           [--count 16384] [--accel SPEC]... [--out docs/results.md] [--plots docs/plots]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_grid2  # noqa: E402
from report import write_markdown  # noqa: E402
from report_common import import_pyplot, provenance, prov_line  # noqa: E402

SCENES = {"flake_meshfloor3": ["flake", "--size", "3", "--as", "mesh"],
          "stadium": ["stadium", "--size", "5"],
          "flake_spheres4": ["flake", "--size", "4"]}
DEFAULT_ACCELS = ["grid:uniform", "grid:two_level", "bvh:binned", "bvh:pbinned", "bvh:sweep",
                  "kdtree:sah", "bvh:pair", "bvh8"]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rtlab", default="build/release/apps/rtlab")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--count", type=int, default=16384)
    ap.add_argument("--accel", action="append")
    ap.add_argument("--out", default="docs/results.md")
    ap.add_argument("--plots", default="docs/plots")
    args = ap.parse_args()
    accels = args.accel or DEFAULT_ACCELS
    tmp = tempfile.mkdtemp()
    run = lambda cmd: subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    for scene, gen in SCENES.items():
        run([args.rtlab, "gen", *gen, "-o", f"{tmp}/{scene}.json"])
        for kind in report_grid2.KINDS:
            run([args.rtlab, "rays", "--scene", f"{tmp}/{scene}.json", "--kind", kind, "--count",
                 str(args.count), "--seed", "1", "-o", f"{tmp}/{scene}.{kind}.rays"])
    results = {}
    for _ in range(args.rounds):
        for scene in SCENES:
            for kind in report_grid2.KINDS:
                for accel in accels:
                    cmd = [args.rtlab, "trace", "--threads", "1", "--stats", "--repeat", "1",
                           "--scene", f"{tmp}/{scene}.json", "--rays", f"{tmp}/{scene}.{kind}.rays",
                           "--accel", accel] + (["--any-hit"] if kind == "shadow" else [])
                    j = json.loads(run(cmd))
                    results.setdefault((j["accel"], scene, kind), []).append(j)
    rows = {}
    for (accel, scene, kind), js in results.items():
        last = js[-1]
        row = {"rays/s": statistics.median(j["mrays_per_s"] for j in js) * 1e6,
               "prims/ray": last["prims_per_ray"], "nodes/ray": last["nodes_per_ray"],
               "cost_model": last["cost_model"], "measured_cost": last["measured_cost"],
               "build_ms": statistics.median(j["build_ms"] for j in js)}
        if "epo" in last:
            row["epo"] = last["epo"]
        rows[f"grid2/trace/{accel}/{scene}/{kind}/threads:1"] = row
        if not scene.startswith("flake_spheres") and kind == "primary":
            rows[f"grid2/build/{accel}/{scene}/threads:1"] = {"build_ms": row["build_ms"]}
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    command = ("python3 bench/grid2_trace_table.py " + " ".join(sys.argv[1:])).strip()
    prov = provenance({}, command, root)
    lines = report_grid2.section(rows, prov_line(prov) + f" Rounds: {args.rounds}, interleaved; "
                                 "one process per trace run; build rows: the tracer's build "
                                 "(one thread, clip callback).", args.plots, import_pyplot())
    write_markdown(args.out, "\n".join(lines) + "\n", report_grid2.BEGIN, report_grid2.END)
    print(f"grid2_trace_table: wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
