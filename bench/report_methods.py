"""The main report's sections on intersection methods: error against run time per primitive kind
(table and Pareto plot) and the root finders on implicit surfaces (bench/report.py's Report).
"""
import os

from report_common import (
    prov_caption,
    save_figure,
    num,
    fmt,
    fmt_rate,
    pareto_front,
    plain_log_axis,
    pareto_plot,
)

SETS = ["random", "edge", "grazing", "far"]


class MethodSections:
    """Mixed into bench/report.py's Report: uses its rows, prov, plots, plt, add, family and image."""

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
        save_figure(fig, path)
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
