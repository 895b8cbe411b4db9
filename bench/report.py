#!/usr/bin/env python3
"""Turn rtlab_bench results into the generated part of docs/results.md and PNG plots.

Runs `rtlab_bench --benchmark_out_format=json` (or reads an existing JSON file) and writes, between
the markers `<!-- report:begin -->` and `<!-- report:end -->` of the Markdown file (appended when
absent, so hand-written sections survive):
  - error against run time for the intersection methods: a table and a Pareto plot per primitive
    kind (x: ns per test, y: false hit + false miss + wrong t rate, one point per method x
    precision);
  - root finders: a table per surface and one Pareto plot (y: median relative t error);
  - Mrays/s per structure, scene and ray kind, with Embree's rows (trace/embree:*) as reference;
  - scaling: build time (and trace time, when the run has a size sweep) against primitive count,
    log-log, with the fitted exponent;
  - heat maps: out/heat-<accel>.png (from `rtlab render --aov heatmap`) when present.
With --sweep T.json (a table of `rtlab sweep merge`) it writes the sweep's report instead
(bench/sweep_report.py): tables and throughput plots per scene, and line plots of Mrays/s and SAH
cost along every swept parameter (e.g. max_leaf), to --out (the whole file) and --plots.
Every table and plot records the command, git revision, compiler and CPU. A benchmark family
missing from the run is skipped with a note.

With --suite issue12 it runs `rtlab_bench --suite issue12` instead and writes issue 12's target
table (measure | target | measured ratio | status, per-structure tables, the headline) between
`<!-- issue12:begin -->` and `<!-- issue12:end -->` (bench/report_issue12.py), leaving the rest
of the file alone. With --suite grid2 it runs `rtlab_bench --suite grid2` and writes issue 16's
two-level grid targets, build times and predicted-against-measured cost table between
`<!-- grid2:begin -->` and `<!-- grid2:end -->` (bench/report_grid2.py), plus
docs/plots/cost-model-scatter.png.

Example: python3 bench/report.py --bench build/release/bench/rtlab_bench --quick \\
             --out docs/results.md --plots docs/plots
         python3 bench/report.py --suite issue12 --out docs/results.md   (6-7 minutes idle)
Smoke test (synthetic data, no executable needed): python3 bench/report.py --self-test
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import report_grid2
import report_issue12
from report_common import (
    import_pyplot,
    provenance,
    prov_line,
    prov_caption,
    to_ms,
    load_rows,
    num,
    fmt,
    fmt_rate,
    pareto_front,
    plain_log_axis,
    pareto_plot,
)

BEGIN = "<!-- report:begin -->"
END = "<!-- report:end -->"
SETS = ["random", "edge", "grazing", "far"]



class Report:
    def __init__(self, rows, prov, out_md, plots_dir, heat_dir, plt):
        self.rows = rows
        self.prov = prov
        self.out_md = out_md
        self.plots = plots_dir
        self.heat_dir = heat_dir
        self.plt = plt
        self.lines = []
        self.written = []

    def rel(self, path):
        return os.path.relpath(path, os.path.dirname(os.path.abspath(self.out_md)) or ".")

    def add(self, *lines):
        self.lines.extend(lines)

    def image(self, path, alt):
        self.written.append(path)
        self.add(f"![{alt}]({self.rel(path)})", "")

    def family(self, prefix):
        return {k: v for k, v in self.rows.items() if k.startswith(prefix)}

    # -- intersectors -------------------------------------------------------------------------
    def intersectors(self):
        fam = self.family("intersect/")
        self.add("## Intersection methods: error against run time", "")
        if not fam:
            self.add("_No `intersect/` benchmarks in this run: section skipped._", "")
            return
        self.add(
            "Each method in float and double traces the cross-check's seeded ray sets "
            "(`crosscheck/ray_sets.h`: random, edge-aimed, grazing, far; spheres and implicit "
            "surfaces have no edges) and is compared with the exact answer of the same oracle as "
            "`rtlab crosscheck` (CGAL, GMP, MPFR), computed once outside the timing. Failure = "
            "false hit + false miss + wrong t (both hit, relative t error above 2^-10 in float, "
            "2^-20 in double: another surface), per ray, as `rtlab crosscheck` counts it; ns/test is the mean over the sets of single-thread "
            "time per ray-primitive test (triangles: a ray against every triangle of a closed "
            "352-triangle mesh, closest hit). Rates come from `rays` rays per set.", "")
        # name: intersect/<prim>/<method>/<precision>/<set>
        kinds = {}
        for name, r in fam.items():
            parts = name.split("/")
            if len(parts) != 5:
                continue
            _, prim, method, prec, set_ = parts
            kinds.setdefault(prim, {}).setdefault((method, prec), {})[set_] = r
        for prim, methods in kinds.items():
            self.add(f"### {prim}", "")
            self.add("| method | precision | ns/test | fail random | fail edge | fail grazing | "
                     "fail far | false hit | false miss | wrong t | median rel t err | "
                     "max rel t err |",
                     "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
            labels, xs, ys = [], [], []
            for (method, prec), sets in methods.items():
                ns = [num(r, "ns/test") for r in sets.values()]
                ns = [v for v in ns if v is not None]
                fail = {s: (num(r, "false_hit_rate") or 0) + (num(r, "false_miss_rate") or 0)
                        + (num(r, "wrong_t_rate") or 0) for s, r in sets.items()}
                fh = sum(num(r, "false_hit_rate") or 0 for r in sets.values()) / len(sets)
                fm = sum(num(r, "false_miss_rate") or 0 for r in sets.values()) / len(sets)
                has_t = any(num(r, "wrong_t_rate") is not None for r in sets.values())
                wt = sum(num(r, "wrong_t_rate") or 0 for r in sets.values()) / len(sets)
                meds = [num(r, "median_rel_t_err") for r in sets.values()]
                maxs = [num(r, "max_rel_t_err") for r in sets.values()]
                meds = [v for v in meds if v is not None]
                maxs = [v for v in maxs if v is not None]
                med = sorted(meds)[len(meds) // 2] if meds else None
                mx = max(maxs) if maxs else None
                mean_ns = sum(ns) / len(ns) if ns else None
                self.add(f"| {method} | {prec} | {fmt(mean_ns)} | "
                         + " | ".join(fmt_rate(fail.get(s)) if s in fail else "n/a"
                                      for s in SETS)
                         + f" | {fmt_rate(fh)} | {fmt_rate(fm)} | "
                         + (fmt_rate(wt) if has_t else "-") + f" | {fmt(med)} | {fmt(mx)} |")
                if mean_ns is not None:
                    labels.append(f"{method} {prec}")
                    xs.append(mean_ns)
                    ys.append(fh + fm + wt)
            self.add("")
            rays = [num(r, "rays") for sets in methods.values() for r in sets.values()]
            rays = [v for v in rays if v]
            floor = 0.3 / max(rays) if rays else 1e-5
            nonzero = [y for y in ys if y > 0]
            if nonzero:
                floor = min(floor, min(nonzero) / 3)
            if labels:
                path = os.path.join(self.plots, f"pareto-{prim}.png")
                pareto_plot(self.plt, path, f"{prim}: failure rate against time per test",
                            "ns per ray-primitive test (log)",
                            "false hit + false miss + wrong t rate (log; all ray sets)", labels,
                            xs, ys,
                            prov_caption(self.prov), floor)
                self.image(path, f"Pareto plot, {prim}")

    # -- root finders -------------------------------------------------------------------------
    def roots(self):
        fam = self.family("roots/")
        self.add("## Root finders on implicit surfaces", "")
        if not fam:
            self.add("_No `roots/` benchmarks in this run: section skipped._", "")
            return
        self.add(
            "Each finder runs in the same frame (clip the ray to the surface's box, quartic over "
            "the window, first root in it) on the cross-check's random, grazing and far rays "
            "together. Reference t: exact Sturm-sequence isolation over the rationals (GMP), "
            "refined by 256-bit MPFR bisection to < 2^-110 relative, then rounded to double. "
            "newton_kK caps Newton (bisection-safeguarded) at K iterations per bracket; bisection "
            "is the plain sign-change baseline (16 march steps). Missed root = the exact "
            "polynomial has a root in the window and the finder reports none; wrong t = a root "
            "more than 2^-10 (float) / 2^-20 (double) relative from the exact first root.", "")
        surfaces = {}
        for name, r in fam.items():
            parts = name.split("/")
            if len(parts) != 4:
                continue
            _, surface, finder, prec = parts
            surfaces.setdefault(surface, []).append((finder, prec, r))
        plt = self.plt
        metrics = [("median_rel_t_err", "median relative t error vs exact (log)"),
                   ("max_rel_t_err", "max relative t error vs exact (log)")]
        fig, axes = plt.subplots(len(metrics), len(surfaces),
                                 figsize=(7.5 * len(surfaces), 5 * len(metrics)), dpi=110,
                                 squeeze=False)
        for col, (surface, items) in enumerate(surfaces.items()):
            self.add(f"### {surface}", "")
            self.add("| finder | precision | ns/ray | missed roots | false hits | wrong t | "
                     "median rel t err | max rel t err |",
                     "|---|---|---:|---:|---:|---:|---:|---:|")
            for finder, prec, r in items:
                self.add(f"| {finder} | {prec} | {fmt(num(r, 'ns/ray'))} | "
                         f"{fmt_rate(num(r, 'missed_root_rate'))} | "
                         f"{fmt_rate(num(r, 'false_hit_rate'))} | "
                         f"{fmt_rate(num(r, 'wrong_t_rate'))} | "
                         f"{fmt(num(r, 'median_rel_t_err'))} | {fmt(num(r, 'max_rel_t_err'))} |")
            self.add("")
            for row, (metric, ylabel) in enumerate(metrics):
                self._roots_panel(axes[row][col], surface, items, metric, ylabel)
        fig.text(0.01, 0.005, prov_caption(self.prov), fontsize=7, color="dimgrey")
        fig.tight_layout(rect=(0, 0.03, 1, 1))
        path = os.path.join(self.plots, "pareto-roots.png")
        fig.savefig(path)
        plt.close(fig)
        self.image(path, "Pareto plot, root finders")

    def _roots_panel(self, ax, surface, items, metric, ylabel):
        """One surface and one error metric: a point per finder x precision, colours = finder,
        circle = float, square = double, outlined = on the Pareto front (also dashed)."""
        from matplotlib.lines import Line2D
        plt = self.plt
        pts = [(f, p, num(r, "ns/ray"), num(r, metric)) for f, p, r in items]
        pts = [q for q in pts if q[2] is not None and q[3] is not None]
        nonzero = [q[3] for q in pts if q[3] > 0]
        floor = min(nonzero) / 4 if nonzero else 1e-18
        xy = [(q[2], q[3] if q[3] > 0 else floor) for q in pts]
        front = pareto_front(xy)
        finders = []
        for q in pts:
            if q[0] not in finders:
                finders.append(q[0])
        cmap = plt.get_cmap("tab10")
        color = {f: cmap(i % 10) for i, f in enumerate(finders)}
        for i, (finder, prec, _, _) in enumerate(pts):
            ax.scatter(xy[i][0], xy[i][1], s=110 if i in front else 55, color=color[finder],
                       marker="o" if prec == "float" else "s", alpha=0.9,
                       edgecolors="black" if i in front else "none", linewidths=1.4, zorder=3)
        if len(front) > 1:
            ax.step([xy[i][0] for i in front], [xy[i][1] for i in front], where="post",
                    color="black", linestyle="--", linewidth=1, zorder=2)
        if any(q[3] == 0 for q in pts):
            ax.axhline(floor, color="grey", linewidth=0.6, linestyle=":")
            ax.text(0.005, floor, "0 (exact)", transform=ax.get_yaxis_transform(), ha="left",
                    va="bottom", fontsize=8, color="grey")
        ax.set_xscale("log")
        ax.set_yscale("log")
        plain_log_axis(ax, "x")
        ax.margins(x=0.1, y=0.15)
        ax.set_xlabel("ns per ray (clip + quartic + first root; log)")
        ax.set_ylabel(ylabel)
        ax.set_title(f"{surface}: {ylabel.split(' vs')[0]} against time")
        ax.grid(True, alpha=0.3)
        handles = [Line2D([], [], marker="o", linestyle="", color=color[f], label=f)
                   for f in finders]
        handles += [Line2D([], [], marker="o", linestyle="", color="grey", label="float"),
                    Line2D([], [], marker="s", linestyle="", color="grey", label="double"),
                    Line2D([], [], marker="o", linestyle="--", color="black",
                           markerfacecolor="white", label="Pareto front")]
        ax.legend(handles=handles, fontsize=7, loc="center right", framealpha=0.85)

    # -- structures ---------------------------------------------------------------------------
    def structures(self):
        fam = self.family("trace/")
        self.add("## Structures: Mrays/s per ray kind", "")
        if not fam:
            self.add("_No `trace/` benchmarks in this run: section skipped._", "")
            return
        self.add("Every structure traces the same fixed rays per scene and ray kind, with the "
                 "threading of bench/trace_bench.cpp. Mrays/s from the `rays/s` counter; "
                 "nodes/ray and prims/ray from the separate counting pass (Embree reports none). "
                 "Embree's rows (**bold**, `embree:*`, when built with Embree) are the reference, "
                 "traced on the same primitives and rays.", "")
        # trace/<accel>/<scene>/<kind>
        scenes = {}
        for name, r in fam.items():
            parts = name.split("/")
            if len(parts) < 4:
                continue
            accel, scene, kind = parts[1], "/".join(parts[2:-1]), parts[-1]
            scenes.setdefault(scene, {}).setdefault(accel, {})[kind] = r
        plt = self.plt
        for scene, accels in scenes.items():
            kinds = []
            for a in accels.values():
                for k in a:
                    if k not in kinds:
                        kinds.append(k)
            self.add(f"### {scene}", "")
            self.add("| structure | " + " | ".join(f"Mrays/s {k}" for k in kinds)
                     + " | nodes/ray | prims/ray | build ms | bytes/prim | SAH cost |",
                     "|---|" + "---:|" * (len(kinds) + 5))
            order = sorted(accels, key=lambda a: (a.startswith("embree"), a))
            for accel in order:
                ks = accels[accel]
                first = next(iter(ks.values()))
                mr = [num(ks[k], "rays/s") if k in ks else None for k in kinds]
                npr = [num(r, "nodes/ray") for r in ks.values() if num(r, "nodes/ray") is not None]
                ppr = [num(r, "prims/ray") for r in ks.values() if num(r, "prims/ray") is not None]
                label = f"**{accel}**" if accel.startswith("embree") else accel
                self.add(f"| {label} | "
                         + " | ".join(fmt(v / 1e6) if v is not None else "-" for v in mr)
                         + f" | {fmt(sum(npr) / len(npr) if npr else None)}"
                         + f" | {fmt(sum(ppr) / len(ppr) if ppr else None)}"
                         + f" | {fmt(num(first, 'build_ms'))} | {fmt(num(first, 'bytes/prim'))}"
                         + f" | {fmt(num(first, 'sah_cost'))} |")
            self.add("", "nodes/ray and prims/ray: mean over the ray kinds.", "")
            # Canonical specs make long labels: the legend goes below the axes, two columns.
            fig, ax = plt.subplots(figsize=(10.5, 4.8 + 0.22 * ((len(order) + 1) // 2)), dpi=110)
            width = 0.8 / max(1, len(order))
            cmap = plt.get_cmap("tab20")
            hatches = ["//", "xx", "\\\\", ".."]
            n_emb = 0
            for ai, accel in enumerate(order):
                vals = [(num(accels[accel][k], "rays/s") or 0) / 1e6 if k in accels[accel]
                        else 0 for k in kinds]
                xs = [ki + (ai - (len(order) - 1) / 2) * width for ki in range(len(kinds))]
                emb = accel.startswith("embree")
                ax.bar(xs, vals, width * 0.95, label=accel,
                       color="lightgrey" if emb else cmap(ai % 20), edgecolor="black",
                       hatch=hatches[n_emb % len(hatches)] if emb else None, linewidth=0.5)
                n_emb += 1 if emb else 0
            ax.set_xticks(range(len(kinds)))
            ax.set_xticklabels(kinds)
            ax.set_ylabel("Mrays/s")
            ax.set_title(f"Traversal throughput, {scene} (hatched grey = Embree reference)")
            ax.grid(True, axis="y", alpha=0.3)
            ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.08))
            fig.text(0.01, 0.005, prov_caption(self.prov), fontsize=7, color="dimgrey")
            fig.tight_layout(rect=(0, 0.06, 1, 1))
            safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", scene)
            path = os.path.join(self.plots, f"mrays-{safe}.png")
            fig.savefig(path)
            plt.close(fig)
            self.image(path, f"Mrays/s, {scene}")

    # -- scaling ------------------------------------------------------------------------------
    def scaling(self):
        self.add("## Scaling with primitive count", "")
        build = self.family("build/")
        series = {}
        # build/<accel>/<scene>/<prim count>/threads:<k>
        for name, r in build.items():
            parts = name.split("/")
            if len(parts) < 5:
                continue
            accel, scene, threads = parts[1], parts[2], parts[-1]
            n = num(r, "prims")
            if n is None:
                try:
                    n = float(parts[3])
                except ValueError:
                    continue
            ms = num(r, "build_ms")
            if ms is None:
                ms = to_ms(float(r.get("real_time", 0)), r.get("time_unit", "ns"))
            series.setdefault((accel, scene, threads), []).append((n, ms))
        trace = {}
        for name, r in self.family("trace/").items():
            parts = name.split("/")
            n = num(r, "prims")
            rps = num(r, "rays/s")
            if len(parts) < 4 or n is None or not rps:
                continue
            # Only sizes of one scene family form a sweep (soup_1000, soup_8000, ...): different
            # scenes are not points of one curve.
            family = re.sub(r"[_-]?\d+$", "", "/".join(parts[2:-1]))
            trace.setdefault((parts[1], family, parts[-1]), []).append((n, 1e9 / rps))
        trace = {k: v for k, v in trace.items() if len({n for n, _ in v}) >= 2}
        if not series and not trace:
            self.add("_No `build/` benchmarks (nor a trace size sweep) in this run: section "
                     "skipped._", "")
            return
        self.add("Least-squares fit of log(time) = a + k log(n) per series: k is the exponent "
                 "(1 = linear; n log n fits k slightly above 1 over a short range).", "")
        if not trace:
            self.add("_Trace time against primitive count: no trace benchmark with a `prims` "
                     "counter over two or more sizes in this run._", "")
        self.add("| family | series | sizes | exponent k | time at largest n |",
                 "|---|---|---:|---:|---:|")
        # Small multiples: one panel per scene family and ray kind (build: per scene), one line
        # per structure in it, the same colour for a structure in every panel, one shared legend.
        panels = {}
        for (accel, scene, threads), pts in series.items():
            label = accel if threads == "threads:1" else f"{accel} ({threads.split(':')[-1]} thr)"
            panels.setdefault(("build", scene), []).append((accel, label, threads, pts))
        for (accel, family, kind), pts in trace.items():
            panels.setdefault(("trace", family, kind), []).append((accel, accel, kind, pts))
        accels = sorted({a for items in panels.values() for a, _, _, _ in items})
        short = {a: a.split(",")[0] for a in accels}
        if len(set(short.values())) < len(accels):
            short = {a: a for a in accels}
        cmap = self.plt.get_cmap("tab10" if len(accels) <= 10 else "tab20")
        color = {a: cmap(i % cmap.N) for i, a in enumerate(accels)}
        plt = self.plt
        ncols = min(3, len(panels))
        nrows = (len(panels) + ncols - 1) // ncols
        fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 4.2 * nrows + 1.2),
                                 dpi=110, squeeze=False)
        for pi, (pkey, items) in enumerate(sorted(panels.items())):
            ax = axes[pi // ncols][pi % ncols]
            fam = pkey[0]
            unit = "ms" if fam == "build" else "ns/ray"
            for accel, label, sub, pts in sorted(items, key=lambda it: it[1]):
                pts = sorted(p for p in pts if p[0] > 0 and p[1] > 0)
                if not pts:
                    continue
                xs = [p[0] for p in pts]
                ys = [p[1] for p in pts]
                k = None
                if len(pts) >= 2 and len(set(xs)) >= 2:
                    lx = [math.log(x) for x in xs]
                    ly = [math.log(y) for y in ys]
                    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
                    sxx = sum((x - mx) ** 2 for x in lx)
                    k = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx
                dashed = accel.startswith("embree") or (fam == "build" and sub != "threads:1")
                ax.plot(xs, ys, marker="s" if fam == "build" and sub != "threads:1" else "o",
                        markersize=3, color=color[accel], linestyle="--" if dashed else "-")
                key = "/".join((accel,) + tuple(pkey[1:]) + ((sub,) if fam == "build" else ()))
                self.add(f"| {fam} | {key} | {len(pts)} | "
                         f"{fmt(k) if k is not None else '-'} | {fmt(ys[-1])} {unit} |")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("primitives (log)", fontsize=8)
            ax.set_ylabel(("build time (ms)" if fam == "build" else "ns per ray") + " (log)",
                          fontsize=8)
            ax.set_title(" / ".join(pkey), fontsize=9)
            ax.tick_params(labelsize=7)
            ax.grid(True, which="both", alpha=0.3)
        for pi in range(len(panels), nrows * ncols):
            axes[pi // ncols][pi % ncols].axis("off")
        from matplotlib.lines import Line2D
        handles = [Line2D([], [], color=color[a], marker="o", markersize=4,
                          linestyle="--" if a.startswith("embree") else "-", label=short[a])
                   for a in accels]
        if series:
            handles.append(Line2D([], [], color="grey", marker="s", markersize=4,
                                  linestyle="--", label="build with 2+ threads"))
        fig.legend(handles=handles, loc="lower center", ncol=min(5, len(handles)), fontsize=8,
                   bbox_to_anchor=(0.5, 0.02), frameon=False)
        fig.suptitle("Time against primitive count, log-log (k per series in the table)",
                     fontsize=11)
        self.add("")
        legend_rows = (len(handles) + 4) // 5
        fig.text(0.01, 0.003, prov_caption(self.prov), fontsize=7, color="dimgrey")
        fig.tight_layout(rect=(0, (0.35 + 0.2 * legend_rows) / (4.2 * nrows + 1.2) + 0.01, 1,
                               0.97))
        path = os.path.join(self.plots, "scaling.png")
        fig.savefig(path)
        plt.close(fig)
        self.image(path, "Scaling, log-log")

    # -- heat maps ----------------------------------------------------------------------------
    def heatmaps(self):
        self.add("## Traversal heat maps", "")
        found = []
        if self.heat_dir and os.path.isdir(self.heat_dir):
            for f in sorted(os.listdir(self.heat_dir)):
                m = re.fullmatch(r"heat-(.+)\.png", f)
                if m:
                    found.append((m.group(1), os.path.join(self.heat_dir, f)))
        if not found:
            self.add(f"_No heat maps (`{self.heat_dir}/heat-<accel>.png`, made by `rtlab render "
                     "--aov heatmap`) found: section skipped._", "")
            return
        self.add("Nodes visited plus primitive tests per pixel (the renderer's heat-map AOV, "
                 "eye rays; the colour bar at the bottom of each image carries its values), one "
                 f"image per structure, copied from `{self.heat_dir}/`.", "")
        self.add("| structure | heat map |", "|---|---|")
        for accel, src in found:
            dst = os.path.join(self.plots, f"heat-{accel}.png")
            if os.path.abspath(src) != os.path.abspath(dst):
                shutil.copyfile(src, dst)
            self.written.append(dst)
            self.add(f"| {accel} | ![{accel}]({self.rel(dst)}) |")
        self.add("")

    def build(self):
        self.add(BEGIN,
                 "<!-- Generated by bench/report.py: edits between these markers are lost. -->",
                 "", "# Benchmark report (generated)", "", prov_line(self.prov), "",
                 f"Google Benchmark library build (Debian's package, not rtlab's code): "
                 f"{self.prov['build']}; wall time of the benchmark run: "
                 f"{self.prov.get('wall', '?')}. Timings are single-machine and noisy (2 shared "
                 "cores): compare rows of one table. Error rates and counts do not depend on the "
                 "machine.", "")
        for section in (self.intersectors, self.roots, self.structures, self.scaling,
                        self.heatmaps):
            try:
                section()
            except Exception as e:  # a broken family must not lose the other sections
                self.add(f"_Section {section.__name__} failed: {type(e).__name__}: {e}_", "")
        self.add(END)
        return "\n".join(self.lines) + "\n"


def write_markdown(path, generated, begin=BEGIN, end=END):
    old = ""
    if os.path.exists(path):
        with open(path) as f:
            old = f.read()
    if begin in old and end in old:
        head, rest = old.split(begin, 1)
        tail = rest.split(end, 1)[1]
        text = head + generated.rstrip("\n") + tail
    elif old:
        text = old.rstrip("\n") + "\n\n" + generated
    else:
        text = "# Results\n\n" + generated
    with open(path, "w") as f:
        f.write(text)


# ---------------------------------------------------------------------------------------------
# Self test


def synthetic():
    rows = []

    def b(name, **counters):
        rows.append(dict(name=name, run_name=name, run_type="iteration", real_time=1.0,
                         cpu_time=1.0, time_unit="us", **counters))

    for prim, methods in (("triangle", ["moller_trumbore", "watertight"]),
                          ("sphere", ["geometric", "stable"])):
        for mi, m in enumerate(methods):
            for pi, p in enumerate(("float", "double")):
                for s in (SETS if prim == "triangle" else ["random", "grazing", "far"]):
                    b(f"intersect/{prim}/{m}/{p}/{s}", **{
                        "ns/test": 10.0 + 3 * mi + 2 * pi, "rays": 1000.0,
                        "false_hit_rate": 0.0 if pi else 0.01 / (mi + 1),
                        "false_miss_rate": 0.002 if mi == 0 and pi == 0 else 0.0,
                        "wrong_t_rate": 0.003 if mi == 0 and pi == 0 else 0.0,
                        "max_rel_t_err": 1e-3 / (1 + 1e6 * pi), "median_rel_t_err": 1e-8})
    for f_i, f in enumerate(["closed_form", "newton_k4", "bisection"]):
        for p in ("float", "double"):
            b(f"roots/torus/{f}/{p}", **{"ns/ray": 100.0 + 50 * f_i, "median_rel_t_err": 1e-7,
                                        "max_rel_t_err": 1e-2, "missed_root_rate": 0.001,
                                        "false_hit_rate": 0.0})
    for a in ("bvh:sweep,max_leaf=4,ct=1,ci=1", "embree:medium"):
        for k in ("primary", "shadow"):
            b(f"trace/{a}/flake/{k}", **{"rays/s": 2e6, "nodes/ray": 20.0, "prims/ray": 3.0,
                                         "build_ms": 5.0, "bytes/prim": 30.0})
        for n in (1000, 10000, 100000):
            b(f"build/{a}/soup/{n}/threads:1/min_time:0.050/manual_time", prims=float(n),
              build_ms=n * 1e-3)
    return {"context": {"date": "synthetic", "num_cpus": 2, "library_build_type": "release"},
            "benchmarks": rows}


def self_test(plt):
    tmp = tempfile.mkdtemp(prefix="report-selftest-")
    md = os.path.join(tmp, "results.md")
    with open(md, "w") as f:
        f.write(f"# Results\n\nhand-written\n\n{BEGIN}\nold\n{END}\n\nafter\n")
    prov = provenance({}, "self-test", os.path.dirname(os.path.abspath(__file__)))
    prov["wall"] = "0 s"
    rep = Report(load_rows(synthetic()), prov, md, tmp, os.path.join(tmp, "none"), plt)
    write_markdown(md, rep.build())
    text = open(md).read()
    checks = {
        "hand-written text kept": "hand-written" in text and "after" in text,
        "old generated text replaced": "\nold\n" not in text,
        "intersector table": "### triangle" in text and "| watertight | double |" in text,
        "roots table": "### torus" in text,
        "structures table": "**embree:medium**" in text,
        # fail = false hit 1% + false miss 0.2% + wrong t 0.3% on every set
        "wrong t counted as failure": "| moller_trumbore | float | 10 | 1.5% | 1.5% | 1.5% | "
        "1.5% | 1% | 0.2% | 0.3% |" in text,
        "scaling fit k=1": "| build | bvh:sweep,max_leaf=4,ct=1,ci=1/soup/threads:1 | 3 | 1 |"
        in text,
        "heat maps skipped": "No heat maps" in text,
        "no failed section": "failed:" not in text,
        "plots written": all(os.path.getsize(p) > 1000 for p in rep.written),
    }
    issue = "\n".join(report_issue12.section(report_issue12.synthetic_rows(), "prov"))
    write_markdown(md, issue + "\n", report_issue12.BEGIN, report_issue12.END)
    text2 = open(md).read()
    checks["issue12 table"] = ("| best rtlab layout / Embree medium, triangles, primary | >= 1.0x "
                               "| 0.667x | 0.52x [0.5, 0.55] | **below target** "
                               "(bvh:pair,from=pbinned) |" in text2 and
                               "| best binary BVH / Embree medium, primary | >= 0.5x | 0.667x | "
                               "0.52x [0.5, 0.55] | met" in text2 and
                               "| best binary BVH / Embree medium, shadow | >= 0.5x | 0.667x | - | "
                               "met" in text2)
    checks["issue12 build row"] = ("bvh:pbinned), 1 thread / Embree medium build, same triangles | "
                                   "<= 1.0x | 1x | 1.04x [1.01, 1.08] | **below target** |"
                                   in text2)
    checks["issue12 scaling rows"] = (
        "| build bvh:pbinned, 2 threads / 1 thread | >= 1.8x | 2x | 1.83x [1.79, 1.9] | met |"
        in text2 and "| trace embree:medium shadow, 2 threads / 1 thread (wall) | >= 1.8x | 2x | "
        "1.7x [1.6, 1.75] | **below target** |" in text2 and
        "| embree:medium | - | - | 1.7x [1.6, 1.75] | - |" in text2)
    checks["issue12 keeps the main report"] = BEGIN in text2 and "### torus" in text2
    checks["issue12 headline"] = "bvh      primary  best bvh:pair,from=pbinned" in text2
    failed = [k for k, ok in checks.items() if not ok]
    shutil.rmtree(tmp)
    print(f"{len(checks) - len(failed)} passed, {len(failed)} failed")
    for k in failed:
        print(f"FAILED: {k}")
    return 1 if failed else 0


# ---------------------------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/release/bench/rtlab_bench",
                    help="rtlab_bench executable to run (ignored with --json)")
    ap.add_argument("--quick", action="store_true", help="pass --quick to rtlab_bench")
    ap.add_argument("--no-interleave", action="store_true",
                    help="run each benchmark's repetitions back to back (default: Google "
                    "Benchmark's random interleaving, so a slow spell of a shared machine falls "
                    "on every row's repetitions alike instead of on a few rows)")
    ap.add_argument("--filter", default="", help="--benchmark_filter regex for rtlab_bench")
    ap.add_argument("--suite", default="all", choices=["all", "issue12", "grid2"],
                    help="issue12: run rtlab_bench --suite issue12 and write the target table; "
                    "grid2: run --suite grid2 and write issue 16's grid and cost-model block and "
                    "plot")
    ap.add_argument("--cpu", action="store_true",
                    help="with --suite issue12: one-thread rows timed by CPU time (shared machine)")
    ap.add_argument("--headline", action="store_true",
                    help="with --suite issue12: also print the headline on stdout")
    ap.add_argument("--json", help="read this benchmark JSON instead of running rtlab_bench")
    ap.add_argument("--save-json", help="also keep the JSON of the run here")
    ap.add_argument("--git", help="git revision the header names (default: this script's "
                    "checkout; give it when the script runs from a copy of the tree without .git)")
    ap.add_argument("--out", default="docs/results.md",
                    help="Markdown file; the part between the report markers is replaced")
    ap.add_argument("--plots", default="docs/plots", help="folder for the PNG plots")
    ap.add_argument("--heatmaps", default="out", help="folder searched for heat-<accel>.png")
    ap.add_argument("--sweep", help="report a merged sweep table (rtlab sweep merge -o T: T.json)")
    ap.add_argument("--self-test", action="store_true",
                    help="run on synthetic data in a temporary folder and check the output")
    args = ap.parse_args()

    plt = import_pyplot()
    if args.self_test:
        return self_test(plt)
    if args.sweep:
        from sweep_report import sweep_report
        with open(args.sweep) as f:
            table = json.load(f)
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        with open(args.out + ".tmp", "w") as f:
            f.write(sweep_report(table, args.sweep, args.plots, plt) + "\n")
        os.replace(args.out + ".tmp", args.out)
        print(f"report: wrote {args.out} (plots in {args.plots})", file=sys.stderr)
        return 0

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if args.json:
        with open(args.json) as f:
            data = json.load(f)
        ctx = data.get("context", {})
        command = ctx.get("rtlab_report_command", "rtlab_bench (command not recorded)")
        command += f"`, rendered by `python3 bench/report.py --json {args.json}"
        wall = ctx.get("rtlab_report_wall", "?")
    else:
        if not os.path.exists(args.bench):
            sys.exit(f"report: no benchmark executable at {args.bench} (build the release "
                     "preset, or pass --json)")
        fd, tmp = tempfile.mkstemp(suffix=".json")
        os.close(fd)
        cmd = [args.bench, f"--benchmark_out={tmp}", "--benchmark_out_format=json"]
        if args.quick:
            cmd.append("--quick")
        if args.suite != "all":
            cmd += ["--suite", args.suite]
        if args.filter:
            cmd.append(f"--benchmark_filter={args.filter}")
        interleave = [] if args.no_interleave else ["--benchmark_enable_random_interleaving=true"]
        cmd += interleave
        print("report: running " + " ".join(cmd), file=sys.stderr)
        start = time.time()
        res = subprocess.run(cmd, stdout=sys.stderr)
        elapsed = time.time() - start
        if res.returncode != 0:
            sys.exit(f"report: rtlab_bench exited with {res.returncode}")
        with open(tmp) as f:
            data = json.load(f)
        os.remove(tmp)
        wall = f"{elapsed:.1f} s"
        data.setdefault("context", {})["rtlab_report_wall"] = wall
        shown = [args.bench] + (["--quick"] if args.quick else []) + (
            ["--suite", args.suite] if args.suite != "all" else []) + (
            [f"--benchmark_filter='{args.filter}'"] if args.filter else []) + interleave
        command = " ".join(shown) + " --benchmark_out_format=json"
        data["context"]["rtlab_report_command"] = command
    if args.git:
        data.setdefault("context", {})["git"] = args.git
    if args.save_json and not args.json:
        with open(args.save_json, "w") as f:
            json.dump(data, f, indent=1)
    prov = provenance(data.get("context", {}), command, root)
    prov["wall"] = wall
    if args.suite == "issue12":
        rows = load_rows(data)
        lines = report_issue12.section(rows, prov_line(prov) + f" Wall time of the run: {wall}.",
                                       args.cpu)
        write_markdown(args.out, "\n".join(lines) + "\n", report_issue12.BEGIN,
                       report_issue12.END)
        if args.headline:
            print("\n".join(report_issue12.Issue12(rows, args.cpu).headline()))
        print(f"report: wrote the issue12 table into {args.out}", file=sys.stderr)
        return 0
    if args.suite == "grid2":
        lines = report_grid2.section(load_rows(data),
                                     prov_line(prov) + f" Wall time of the run: {wall}.",
                                     args.plots, plt)
        write_markdown(args.out, "\n".join(lines) + "\n", report_grid2.BEGIN, report_grid2.END)
        print(f"report: wrote the grid2 block into {args.out}", file=sys.stderr)
        return 0
    os.makedirs(args.plots, exist_ok=True)
    rep = Report(load_rows(data), prov, args.out, args.plots, args.heatmaps, plt)
    write_markdown(args.out, rep.build())
    print(f"report: wrote {args.out} and {len(rep.written)} images in {args.plots}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
