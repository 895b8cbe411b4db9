"""The two-level grid's targets and the cost-model figures from an `rtlab_bench --suite grid2`
run (bench/grid2_bench.cpp); used by report.py --suite grid2.

Row names: grid2/trace/<accel>/<scene>/<kind>/threads:1 and grid2/build/<accel>/<scene>/
threads:<k>, <accel> a canonical registry spec. Writes the block between `<!-- grid2:begin -->`
and `<!-- grid2:end -->` of docs/results.md and docs/plots/cost-model-scatter.png (predicted
against measured cost, one point per structure and scene and ray kind).
"""
import os
import re

from report_common import fmt, num, save_figure

BEGIN = "<!-- grid2:begin -->"
END = "<!-- grid2:end -->"
KINDS = ["primary", "shadow", "diffuse"]
TRACE = re.compile(r"grid2/trace/(?P<accel>[^/]+)/(?P<scene>[^/]+)/(?P<kind>[^/]+)/threads:1$")
BUILD = re.compile(r"grid2/build/(?P<accel>[^/]+)/(?P<scene>[^/]+)/threads:(?P<threads>\d+)$")
# Structures whose build optimises the SAH (the targets' "SAH-quality" rows); layouts converted
# from such a tree (bvh4, bvh8, bvh:pair from pbinned) count too.
SAH_NAMES = ("bvh:binned", "bvh:pbinned", "bvh:sweep", "kdtree:sah", "bvh4", "bvh8", "bvh:pair")


def name_of(accel):
    return accel.split(",", 1)[0]


def short(accel):
    parts = accel.split(",")
    keep = [p for p in parts[1:] if p.startswith("from=")]
    return ",".join([parts[0]] + keep)


def is_sah(accel):
    n = name_of(accel)
    return n in SAH_NAMES and ("from=" not in accel or "from=pbinned" in accel
                               or "from=binned" in accel or "from=sweep" in accel)


class Grid2:
    def __init__(self, rows):
        self.trace = {}  # (accel, scene, kind) -> row
        self.build = {}  # (accel, scene, threads) -> build_ms
        for name, row in rows.items():
            m = TRACE.match(name)
            if m:
                self.trace[(m["accel"], m["scene"], m["kind"])] = row
                continue
            m = BUILD.match(name)
            if m:
                self.build[(m["accel"], m["scene"], int(m["threads"]))] = num(row, "build_ms")
        self.accels = sorted({k[0] for k in self.trace} | {k[0] for k in self.build},
                             key=lambda a: (name_of(a).split(":")[0], a))
        self.scenes = sorted({k[1] for k in self.trace})
        self.mesh_scenes = sorted({k[1] for k in self.build})

    def get(self, accel, scene, kind, key):
        row = self.trace.get((accel, scene, kind))
        return None if row is None else num(row, key)

    def find(self, name):
        for a in self.accels:
            if name_of(a) == name:
                return a
        return None

    def mrays(self, accel, scene, kind):
        r = self.get(accel, scene, kind, "rays/s")
        return None if r is None else r / 1e6

    def target_table(self):
        uni, two, bin_ = self.find("grid:uniform"), self.find("grid:two_level"), \
            self.find("bvh:binned")
        out = ["| scene | rays | prims/ray uniform | prims/ray two-level | ratio (target <= 0.2) "
               "| Mrays/s two-level | Mrays/s bvh:binned | ratio (target >= 0.5) "
               "| best binary BVH | ratio to it |",
               "|---|---|---:|---:|---:|---:|---:|---:|---|---:|"]
        if not (uni and two and bin_):
            return out + ["| (the run lacks grid:uniform, grid:two_level or bvh:binned) |"]
        for scene in self.mesh_scenes:
            for kind in KINDS:
                pu = self.get(uni, scene, kind, "prims/ray")
                p2 = self.get(two, scene, kind, "prims/ray")
                m2, mb = self.mrays(two, scene, kind), self.mrays(bin_, scene, kind)
                best, best_m = None, None
                for a in self.accels:
                    if name_of(a).startswith("bvh:"):
                        m = self.mrays(a, scene, kind)
                        if m is not None and (best_m is None or m > best_m):
                            best, best_m = a, m
                pr = p2 / pu if p2 is not None and pu else None
                mr = m2 / mb if m2 is not None and mb else None
                br = m2 / best_m if m2 is not None and best_m else None
                out.append(f"| {scene} | {kind} | {fmt(pu)} | {fmt(p2)} | "
                           f"{fmt(pr)} {'ok' if pr is not None and pr <= 0.2 else 'MISSED'} | "
                           f"{fmt(m2)} | {fmt(mb)} | "
                           f"{fmt(mr)} {'ok' if mr is not None and mr >= 0.5 else 'MISSED'} | "
                           f"{short(best) if best else '-'} | {fmt(br)} |")
        return out

    def build_table(self):
        out = ["| structure | SAH quality | " + " | ".join(
            f"{s} 1 thread ms | {s} 2 threads ms | {s} in the tracer, 1 thread, clipped ms"
            for s in self.mesh_scenes) + " |",
            "|---|---|" + "---:|---:|---:|" * len(self.mesh_scenes)]
        for a in self.accels:
            cells = []
            for s in self.mesh_scenes:
                cells += [fmt(self.build.get((a, s, 1))), fmt(self.build.get((a, s, 2))),
                          fmt(self.get(a, s, "primary", "build_ms"))]
            out.append(f"| {short(a)} | {'yes' if is_sah(a) else ''} | " + " | ".join(cells) + " |")
        two = self.find("grid:two_level")
        for s in self.mesh_scenes:
            sah = [(self.build.get((a, s, 1)), a) for a in self.accels
                   if is_sah(a) and self.build.get((a, s, 1)) is not None]
            t = self.build.get((two, s, 1)) if two else None
            if sah and t is not None:
                fastest, which = min(sah)
                out.append("")
                verdict = "fastest" if t <= fastest else "not the fastest"
                out.append(f"{s}, one thread: grid:two_level builds in {fmt(t)} ms, the fastest "
                           f"SAH-quality structure ({short(which)}) in {fmt(fastest)} ms: the "
                           f"two-level grid takes {fmt(t / fastest)}x its time ({verdict}).")
        return out

    def cost_table(self):
        out = ["| structure | scene | cost_model | measured_cost primary | measured / model "
               "| measured_cost diffuse | epo |",
               "|---|---|---:|---:|---:|---:|---:|"]
        for a in self.accels:
            for s in self.scenes:
                model = self.get(a, s, "primary", "cost_model")
                meas = self.get(a, s, "primary", "measured_cost")
                diff = self.get(a, s, "diffuse", "measured_cost")
                epo = self.get(a, s, "primary", "epo")
                ratio = meas / model if meas is not None and model else None
                out.append(f"| {short(a)} | {s} | {fmt(model)} | {fmt(meas)} | {fmt(ratio)} | "
                           f"{fmt(diff)} | {fmt(epo)} |")
        return out

    def scatter(self, plt, path, caption):
        fig, ax = plt.subplots(figsize=(8.5, 6.5), dpi=110)
        markers = {k: m for k, m in zip(KINDS, ["o", "s", "^"])}
        families = sorted({name_of(a).split(":")[0] for a in self.accels})
        colors = {f: plt.cm.tab10(i % 10) for i, f in enumerate(families)}
        xs_all, ys_all = [], []
        for a in self.accels:
            for s in self.scenes:
                for kind in KINDS:
                    x = self.get(a, s, kind, "cost_model")
                    y = self.get(a, s, kind, "measured_cost")
                    if not x or not y:
                        continue
                    xs_all.append(x)
                    ys_all.append(y)
                    ax.scatter([x], [y], marker=markers[kind],
                               color=colors[name_of(a).split(":")[0]], s=28, alpha=0.8)
                    if kind == "primary":
                        ax.annotate(f"{short(a)} {s}", (x, y), fontsize=5.5, alpha=0.7,
                                    xytext=(3, 2), textcoords="offset points")
        if xs_all:
            lo = min(xs_all + ys_all) * 0.7
            hi = max(xs_all + ys_all) * 1.4
            ax.plot([lo, hi], [lo, hi], color="gray", linewidth=0.8, linestyle="--",
                    label="measured = predicted")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("predicted cost per ray (cost_model: ct * E[nodes] + ci * E[prims])")
        ax.set_ylabel("measured cost per ray (ct * nodes/ray + ci * prims/ray)")
        ax.set_title("One cost model: predicted against measured, per structure, scene, ray kind")
        from matplotlib.lines import Line2D
        handles = [Line2D([], [], marker="o", linestyle="", color=colors[f], label=f)
                   for f in families]
        handles += [Line2D([], [], marker=markers[k], linestyle="", color="black", label=k)
                    for k in KINDS]
        ax.legend(handles=handles, fontsize=7, loc="upper left")
        fig.text(0.01, 0.005, caption, fontsize=6)
        fig.tight_layout(rect=(0, 0.03, 1, 1))
        save_figure(fig, path)
        plt.close(fig)


def section(rows, prov, plots_dir, plt):
    g = Grid2(rows)
    os.makedirs(plots_dir, exist_ok=True)
    path = os.path.join(plots_dir, "cost-model-scatter.png")
    g.scatter(plt, path, prov[:300])
    rel = os.path.relpath(path, "docs") if plots_dir.startswith("docs") else path
    return [BEGIN,
            "<!-- Generated by bench/report.py --suite grid2: edits between these markers are "
            "lost. -->",
            "",
            "### Two-level grid targets and the one cost model (generated)",
            "",
            prov,
            "",
            "One process, TBB limited to one thread; Mrays/s are medians of the repetitions; "
            "prims/ray and nodes/ray come from a separate counting pass.",
            "",
            "#### Two-level grid against the uniform grid and the binary BVH",
            "",
            *g.target_table(),
            "",
            "#### Build times",
            "",
            "Build rows: from the scene's triangle bounds alone (no clip callback), median of the "
            "timed builds, TBB limited to 1 or 2 threads. \"In the tracer\": SceneTracer's build "
            "of the traced structure (with the triangle clip callback, which the grids use to list "
            "a triangle only in cells it really crosses and kd-trees for perfect splits), one "
            "thread, one build.",
            "",
            *g.build_table(),
            "",
            "#### Predicted (cost_model) against measured cost, and EPO",
            "",
            *g.cost_table(),
            "",
            f"![predicted against measured cost]({rel})",
            "",
            END]
