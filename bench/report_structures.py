"""The main report's sections on structures: Mrays/s per structure, scene and ray kind, scaling with
primitive count (log-log, with the fitted exponent) and traversal heat maps (bench/report.py's
Report).
"""
import math
import os
import re
import shutil

from report_common import (
    prov_caption,
    save_figure,
    throughput_bars,
    to_ms,
    num,
    fmt,
)


def scaling_series(build, traces):
    """Build times per (structure, scene, threads) and, for a trace size sweep, ns per ray per
    (structure, scene family, ray kind): lists of (primitive count, time)."""
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
    for name, r in traces.items():
        parts = name.split("/")
        n = num(r, "prims")
        rps = num(r, "rays/s")
        if len(parts) < 4 or n is None or not rps:
            continue
        # Only sizes of one scene family form a sweep (soup_1000, soup_8000, ...): different
        # scenes are not points of one curve.
        family = re.sub(r"[_-]?\d+$", "", "/".join(parts[2:-1]))
        trace.setdefault((parts[1], family, parts[-1]), []).append((n, 1e9 / rps))
    # Two sizes give a line through two noisy points, not an exponent: a series needs three.
    trace = {k: v for k, v in trace.items() if len({n for n, _ in v}) >= 3}
    return series, trace


def loglog_exponent(xs, ys):
    """Least-squares k of log(y) = a + k log(x); None with fewer than two distinct x."""
    if len(xs) < 2 or len(set(xs)) < 2:
        return None
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((x - mx) ** 2 for x in lx)
    return sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx


class StructureSections:
    """Mixed into bench/report.py's Report: uses its rows, prov, plots, heat_dir, plt, add, family and
    image."""

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
            cmap = plt.get_cmap("tab20")
            hatches = ["//", "xx", "\\\\", ".."]
            series = []
            n_emb = 0
            for ai, accel in enumerate(order):
                vals = [(num(accels[accel][k], "rays/s") or 0) / 1e6 if k in accels[accel]
                        else 0 for k in kinds]
                emb = accel.startswith("embree")
                series.append((accel, vals, {
                    "color": "lightgrey" if emb else cmap(ai % 20),
                    "hatch": hatches[n_emb % len(hatches)] if emb else None}))
                n_emb += 1 if emb else 0
            safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", scene)
            path = os.path.join(self.plots, f"mrays-{safe}.png")
            throughput_bars(plt, path, kinds, series,
                            f"Traversal throughput, {scene} (hatched grey = Embree reference)",
                            prov_caption(self.prov), 0.06)
            self.image(path, f"Mrays/s, {scene}")

    # -- scaling ------------------------------------------------------------------------------
    def scaling(self):
        self.add("## Scaling with primitive count", "")
        series, trace = scaling_series(self.family("build/"), self.family("trace/"))
        if not series and not trace:
            self.add("_No `build/` benchmarks (nor a trace size sweep) in this run: section "
                     "skipped._", "")
            return
        self.add("Least-squares fit of log(time) = a + k log(n) per series: k is the exponent "
                 "(1 = linear; n log n fits k slightly above 1 over a short range).", "")
        if not trace:
            self.add("_Trace time against primitive count: no trace benchmark with a `prims` "
                     "counter over three or more sizes in this run._", "")
        self.add("| family | series | sizes | exponent k | time at largest n |",
                 "|---|---|---:|---:|---:|")
        self._scaling_figure(series, trace)

    def _scaling_figure(self, series, trace):
        """The table rows of every series and their small multiples, scaling.png in the plots folder."""
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
                k = loglog_exponent(xs, ys)
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
        save_figure(fig, path)
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
