"""The BVH layouts' target table against Embree from an `rtlab_bench --suite targets` run
(bench/targets_bench.cpp, bench/embree_pairs.cpp); used by report.py --suite targets.

Row names: targets/trace/<accel>/<default|watertight>/<plain|robust>/<scene>/<kind>/threads:<k>,
targets/build/<accel>/<scene>/threads:<k> and
targets/paired/<accel>/<default|watertight>/<plain|robust>/<scene>/<kind>/threads:1 (counters
ratio, ratio_q1, ratio_q3: ours against Embree medium timed in alternation) and
targets/paired_build/<accel>/<scene>/threads:1 (the same counters for builds: our time over
Embree medium's, lower is faster) and targets/scaling/<accel>/<build|kind>/<scene>/threads:2 (the
same counters for one thread against two in alternation: the speed-up), where <accel> is a
canonical registry spec or embree:<quality>. "Best rtlab layout" is the best over every registry
spec in the run (all BVH layouts, binary and wide, whichever are registered) by paired ratio where
the run has paired rows for that scene and kind, else by median rays/s; "binary" are the specs
named bvh:...; a structure family is the spec name before its first ':' or ','.
"""
import re

from report_common import fmt, num, to_ms

BEGIN = "<!-- targets:begin -->"
END = "<!-- targets:end -->"
KINDS = ["primary", "shadow", "diffuse"]
TRACE = re.compile(r"targets/trace/(?P<accel>[^/]+)/(?P<methods>[^/]+)/(?P<mode>[^/]+)/"
                   r"(?P<scene>[^/]+)/(?P<kind>[^/]+)/threads:(?P<threads>\d+)$")
BUILD = re.compile(r"targets/build/(?P<accel>[^/]+)/(?P<scene>[^/]+)/threads:(?P<threads>\d+)$")
PAIRED = re.compile(r"targets/paired/(?P<accel>[^/]+)/(?P<methods>[^/]+)/(?P<mode>[^/]+)/"
                    r"(?P<scene>[^/]+)/(?P<kind>[^/]+)/threads:1$")
PAIRED_BUILD = re.compile(r"targets/paired_build/(?P<accel>[^/]+)/(?P<scene>[^/]+)/threads:1$")
SCALING = re.compile(r"targets/scaling/(?P<accel>[^/]+)/(?P<what>[^/]+)/(?P<scene>[^/]+)/"
                     r"threads:2$")


def family(accel):
    return re.split(r"[:,]", accel, maxsplit=1)[0]


def short(accel):
    """The spec without parameters at their defaults is too long for a table: name + from=, and
    bounds= when it is not the boxes alone."""
    parts = accel.split(",")
    keep = [p for p in parts[1:]
            if p.startswith("from=") or (p.startswith("bounds=") and p != "bounds=aabb")]
    return ",".join([parts[0]] + keep)


class Targets:
    def __init__(self, rows, cpu=False):
        # cpu: one-thread rows use the measuring thread's CPU time instead of wall time (with
        # one thread all the work runs on it), the fair basis on a machine shared with other
        # jobs; two-thread rows always use wall time.
        self.cpu = cpu
        self.trace = {}  # (accel, methods, mode, scene, kind, threads) -> rays/s
        self.counts = {}  # same key -> row
        self.build = {}  # (accel, scene, threads) -> build_ms
        self.build_rows = {}
        self.wall, self.build_wall = {}, {}  # wall-time figures, for the 2 / 1 thread ratios
        # (accel, methods, mode, scene, kind) -> (median, low, high) against Embree medium
        self.paired = {}
        self.paired_build = {}  # (accel, scene) -> (median, low, high) of our build time / Embree's
        self.scaling = {}  # (accel, "build" or kind, scene) -> (median, low, high) of t1 / t2
        # Paired rows' (median, low, high): with repetitions, the median of their ratios and the
        # lowest and highest (reps True); from a run of one repetition, its median and quartiles.
        self.reps = False
        self.timing = {}  # "trace", "build" or "scaling" -> (repetitions, pairs per repetition)
        for name, row in rows.items():
            m = SCALING.match(name)
            if m:
                self.scaling[(m["accel"], m["what"], m["scene"])] = self.paired_ratio(row,
                                                                                       "scaling")
                continue
            m = PAIRED_BUILD.match(name)
            if m:
                self.paired_build[(m["accel"], m["scene"])] = self.paired_ratio(row, "build")
                continue
            m = PAIRED.match(name)
            if m:
                self.paired[(m["accel"], m["methods"], m["mode"], m["scene"], m["kind"])] = (
                    self.paired_ratio(row, "trace"))
                continue
            m = TRACE.match(name)
            if m:
                key = (m["accel"], m["methods"], m["mode"], m["scene"], m["kind"],
                       int(m["threads"]))
                rate = num(row, "rays/s")
                self.wall[key] = rate
                real, cpu_t = num(row, "real_time"), num(row, "cpu_time")
                if cpu and key[5] == 1 and rate and real and cpu_t:
                    rate = rate * real / cpu_t
                self.trace[key] = rate
                self.counts[key] = row
                continue
            m = BUILD.match(name)
            if m:
                key = (m["accel"], m["scene"], int(m["threads"]))
                ms = num(row, "build_ms")
                self.build_wall[key] = ms
                if cpu and key[2] == 1 and num(row, "cpu_time"):
                    ms = to_ms(num(row, "cpu_time"), row.get("time_unit", "ms"))
                self.build[key] = ms
                self.build_rows[key] = row
        scenes = sorted({k[3] for k in self.trace})
        self.mesh = next((s for s in scenes if s.startswith("flake_meshfloor")), None)
        self.spheres = [s for s in scenes if s.startswith("flake_spheres")]
        self.ours = sorted({k[0] for k in self.trace if not k[0].startswith("embree:")})

    def paired_ratio(self, row, kind):
        """A paired row's (median, low, high) (see self.reps); notes how its kind was timed."""
        self.timing.setdefault(kind, (int(row.get("repetitions") or 1),
                                      int(num(row, "pairs") or 0)))
        aggs = row.get("aggregates", {})
        if "min" in aggs and "max" in aggs:
            self.reps = True
            return num(row, "ratio"), num(aggs["min"], "ratio"), num(aggs["max"], "ratio")
        return num(row, "ratio"), num(row, "ratio_q1"), num(row, "ratio_q3")

    def pairs(self, kind):
        """How a kind of paired row was timed (as the run's rows say), and what its brackets
        show."""
        reps, pairs = self.timing.get(kind, (1, 0))
        if self.reps:
            return (f"{reps} repetitions of {pairs} pairs spread over the run by random "
                    "interleaving; the median of the repetitions' medians [the lowest, the "
                    "highest]")
        return f"{pairs} pairs; the median [quartiles]"

    def rate(self, accel, scene, kind, threads=1, methods="default", mode="plain"):
        return self.trace.get((accel, methods, mode, scene, kind, threads))

    def best(self, scene, kind, pred=lambda a: True):
        cands = [(self.rate(a, scene, kind), a) for a in self.ours if pred(a)]
        cands = [(r, a) for r, a in cands if r]
        return max(cands) if cands else (None, None)

    @staticmethod
    def ratio(a, b):
        return a / b if a and b else None

    @staticmethod
    def status(r, target, higher=True):
        if r is None:
            return "not measured"
        ok = r >= float(target) if higher else r <= float(target)
        return "met" if ok else "**below target**"

    def row(self, measure, target, r, higher=True, note="", paired=None):
        """A target row; a paired ratio (median, q1, q3), when the run has one, decides it."""
        op = ">=" if higher else "<="
        p = "-"
        if paired and paired[0] is not None:
            p = f"{fmt(paired[0])}x [{fmt(paired[1])}, {fmt(paired[2])}]"
            r_status = paired[0]
        else:
            r_status = r
        return (f"| {measure} | {op} {target}x | {fmt(r)}x | {p} | "
                f"{self.status(r_status, target, higher)}{' (' + note + ')' if note else ''} |")

    def pair(self, accel, scene, kind, methods="default", mode="plain"):
        return self.paired.get((accel, methods, mode, scene, kind)) if accel else None

    def best_vs_embree(self, scene, kind, pred=lambda a: True):
        """The best layout against Embree: by paired ratio among the layouts the run paired,
        else by median rays/s; with its rays/s."""
        cands = [(p[0], a) for (a, m, mo, sc, k), p in self.paired.items()
                 if (m, mo, sc, k) == ("default", "plain", scene, kind) and p[0] and pred(a)]
        if cands:
            a = max(cands)[1]
            return self.rate(a, scene, kind), a
        return self.best(scene, kind, pred)

    def table(self):
        spread = "[lowest, highest repetition]" if self.reps else "[quartiles]"
        out = [f"| measure | target | ratio of medians | paired ratio, median {spread} | "
               "status |", "|---|---|---|---|---|"]
        emb = "embree:medium"
        for kind in KINDS:
            r, a = self.best_vs_embree(self.mesh, kind)
            out.append(self.row(f"best rtlab layout / Embree medium, triangles, {kind}", "1.0",
                                self.ratio(r, self.rate(emb, self.mesh, kind)),
                                note=f"{short(a)}" if a else "",
                                paired=self.pair(a, self.mesh, kind)))
        for kind in KINDS:
            r, a = self.best_vs_embree(self.mesh, kind)
            wt = self.rate(a, self.mesh, kind, methods="watertight", mode="robust") if a else None
            out.append(self.row(f"watertight + robust on the fastest layout / Embree medium, "
                                f"{kind}", "0.8", self.ratio(wt, self.rate(emb, self.mesh, kind)),
                                note=f"{short(a)}; leaks: docs/stability.md" if a else "",
                                paired=self.pair(a, self.mesh, kind, "watertight", "robust")))
        for kind in KINDS:
            r, a = self.best_vs_embree(self.mesh, kind, lambda s: s.startswith("bvh:"))
            out.append(self.row(f"best binary BVH / Embree medium, {kind}", "0.5",
                                self.ratio(r, self.rate(emb, self.mesh, kind)),
                                note=short(a) if a else "", paired=self.pair(a, self.mesh, kind)))
        for scene in self.spheres:
            for kind in KINDS:
                r, a = self.best_vs_embree(scene, kind)
                out.append(self.row(f"analytic spheres {scene} / Embree spheres, {kind}", "1.5",
                                    self.ratio(r, self.rate(emb, scene, kind)),
                                    note=short(a) if a else "", paired=self.pair(a, scene, kind)))
        pb = next((a for a in self.ours if a.startswith("bvh:pbinned")), None)
        if pb:
            out.append(self.row("binned SAH build (bvh:pbinned), 1 thread / Embree medium build, "
                                "same triangles", "1.0",
                                self.ratio(self.build.get((pb, self.mesh, 1)),
                                           self.build.get((emb, self.mesh, 1))), higher=False,
                                paired=self.paired_build.get((pb, self.mesh))))
        _, fast = self.best_vs_embree(self.mesh, "primary")
        if fast and not fast.startswith("bvh:pbinned"):
            # Embree medium builds a BVH8 whose SAH stops at ranges of up to 4 triangles (its
            # minLeafSize and 4-triangle blocks); the fastest layout's source tree (larger leaves,
            # ct 4) is the build of comparable work, so it is shown beside the binary default.
            out.append(self.row(f"binned SAH build of the fastest layout ({short(fast)}: source "
                                "tree and collapse), 1 thread / Embree medium build",
                                "1.0", self.ratio(self.build.get((fast, self.mesh, 1)),
                                                  self.build.get((emb, self.mesh, 1))),
                                higher=False, paired=self.paired_build.get((fast, self.mesh))))
        for a in self.ours + ["embree:medium", "embree:high"]:
            r = self.ratio(self.build_wall.get((a, self.mesh, 1)),
                           self.build_wall.get((a, self.mesh, 2)))
            if r is not None:
                out.append(self.row(f"build {short(a)}, 2 threads / 1 thread", "1.8", r,
                                    paired=self.scaling.get((a, "build", self.mesh))))
        for kind in KINDS:
            _, a = self.best_vs_embree(self.mesh, kind)
            w = lambda acc, t: self.wall.get((acc, "default", "plain", self.mesh, kind, t))
            for acc in ([a] if a else []) + [emb]:
                out.append(self.row(f"trace {short(acc)} {kind}, 2 threads / 1 thread (wall)",
                                    "1.8", self.ratio(w(acc, 2), w(acc, 1)),
                                    paired=self.scaling.get((acc, kind, self.mesh))))
        return out

    def scaling_table(self):
        """Every structure's paired two-thread / one-thread speed-ups (build and each ray kind)."""
        accs = sorted({k[0] for k in self.scaling if k[2] == self.mesh},
                      key=lambda a: (a.startswith("embree:"), a))
        if not accs:
            return []
        out = [f"Two threads / one thread on {self.mesh}, paired (`targets/scaling/...`: the same "
               "build or pass over the rays with TBB limited to one thread and to two, in "
               f"alternation, {self.pairs('scaling')} of the per-pair speed-ups; a pair shares the "
               "machine's load, so this is the figure the status takes):", "",
               "| structure | build | " + " | ".join(KINDS) + " |", "|---|---|---|---|---|"]
        for a in accs:
            cells = []
            for what in ["build"] + KINDS:
                p = self.scaling.get((a, what, self.mesh))
                cells.append(f"{fmt(p[0])}x [{fmt(p[1])}, {fmt(p[2])}]" if p else "-")
            out.append(f"| {short(a)} | " + " | ".join(cells) + " |")
        return out + [""]

    def detail(self):
        out = [f"Mrays/s, one thread, {self.mesh} (triangles); nodes and primitive tests per ray "
               "from the counting pass (Embree reports none):", "",
               "| structure | " + " | ".join(KINDS) + " | nodes/ray (primary) | prims/ray "
               "(primary) | watertight+robust primary |", "|---|---|---|---|---|---|---|"]
        for a in self.ours + ["embree:medium", "embree:high"]:
            cells = [fmt((self.rate(a, self.mesh, k) or 0) / 1e6) for k in KINDS]
            row = self.counts.get((a, "default", "plain", self.mesh, "primary", 1), {})
            wt = self.rate(a, self.mesh, "primary", methods="watertight", mode="robust")
            out.append(f"| {short(a)} | " + " | ".join(cells) +
                       f" | {fmt(num(row, 'nodes/ray'))} | {fmt(num(row, 'prims/ray'))} | "
                       f"{fmt(wt / 1e6) if wt else '-'} |")
        out.append("")
        for scene in self.spheres:
            out += [f"Mrays/s, one thread, {scene} (analytic spheres):", "",
                    "| structure | " + " | ".join(KINDS) + " |", "|---|---|---|---|"]
            for a in self.ours + ["embree:medium", "embree:high"]:
                cells = [fmt((self.rate(a, scene, k) or 0) / 1e6) for k in KINDS]
                out.append(f"| {short(a)} | " + " | ".join(cells) + " |")
            out.append("")
        out += [f"Memory per triangle on {self.mesh}: structure (nodes and index lists) plus leaf "
                "data (what traversal reads beside the nodes: SIMD leaf blocks with their ids, "
                "padding slots included, or prepared triangles and the 4-byte id map); "
                "Embree: every byte its memory monitor saw for the scene (its vertex and index "
                "copies and the BVH with its leaf triangles). Build: median of 5 builds from "
                "the triangle boxes (ours) or of rtcCommitScene (Embree).", "",
                "| structure | structure B/tri | leaf data B/tri | total B/tri | build ms, 1 thread "
                "| build ms, 2 threads |", "|---|---|---|---|---|---|"]
        for a in self.ours + ["embree:medium", "embree:high"]:
            row = self.counts.get((a, "default", "plain", self.mesh, "primary", 1), {})
            s, leaf = num(row, "bytes/prim"), num(row, "leaf_bytes/prim")
            total = (s or 0) + (leaf or 0) if s is not None else None
            out.append(f"| {short(a)} | {fmt(s) if not a.startswith('embree') else '-'} | "
                       f"{fmt(leaf) if leaf is not None else '-'} | {fmt(total)} | "
                       f"{fmt(self.build.get((a, self.mesh, 1)))} | "
                       f"{fmt(self.build.get((a, self.mesh, 2)))} |")
        out.append("")
        return out

    def headline(self):
        """Each structure family's best layout against Embree medium (mesh scene, 1 thread): by
        paired ratio where the run paired the family (printed beside the medians' ratio), else by
        median rays/s."""
        out = []
        for fam in sorted({family(a) for a in self.ours}):
            for kind in KINDS:
                r, a = self.best_vs_embree(self.mesh, kind, lambda s, f=fam: family(s) == f)
                e = self.rate("embree:medium", self.mesh, kind)
                p = self.pair(a, self.mesh, kind)
                paired = f"; paired {fmt(p[0])}x [{fmt(p[1])}, {fmt(p[2])}]" if p else ""
                out.append(f"{fam:8s} {kind:8s} best {short(a) if a else '-':28s} "
                           f"{fmt((r or 0) / 1e6)} Mrays/s = {fmt(self.ratio(r, e))}x Embree "
                           f"medium ({fmt((e or 0) / 1e6)} Mrays/s){paired}")
        return out


def section(rows, prov_line, cpu=False):
    rep = Targets(rows, cpu)
    if rep.mesh is None:
        return [BEGIN, "_No targets rows in this run._", END]
    lines = [BEGIN,
             "<!-- Generated by bench/report.py --suite targets: edits between these markers "
             "are lost. -->", "", "### The target table (generated)", "", prov_line, "",
             "One thread unless stated; medians of 5 repetitions; all rows of one run on the same "
             "primitives and rays (SPD-view primary rays, shadow rays to a light with any hit, one "
             "cosine diffuse bounce). Embree 3 with `rtcIntersect1`/`rtcOccluded1`. The best "
             "rtlab layout is the best registry row in the run for that scene and ray kind. "
             "Ratio of medians: our median rays/s over Embree's, each from its own benchmark. "
             "Paired ratio (`targets/paired/...` rows, the wide layouts and bvh:pair): ours and "
             "Embree medium timed in alternation, each sample at least 20 ms of warm passes, "
             f"{rep.pairs('trace')} of the per-pair ratios; load on a shared machine "
             "slows both halves of a pair, so it is the steadier figure: where the run has "
             "paired rows, the best layout is the one with the best paired ratio, and the paired "
             "ratio decides the status. The one-thread build rows against Embree have one too "
             "(`targets/paired_build/...`: our build and Embree medium's commit in alternation, "
             f"{rep.pairs('build')} of our time over Embree's), and so do the two-thread / "
             "one-thread rows (`targets/scaling/...`: one thread and two in alternation, "
             f"{rep.pairs('scaling')} of the speed-ups; the wide layouts, bvh:pair and Embree "
             "medium for traces, every structure for builds; table under Per structure). "
             + ("Basis: CPU time of the measuring thread for one-thread rows (`--cpu`: the "
                "machine was shared, and with one thread all work runs on that thread), wall "
                "time for two-thread rows (which a shared machine distorts)." if rep.cpu else
                "Basis: wall time."), ""]
    lines += rep.table()
    lines += ["", "#### Per structure", ""]
    lines += rep.detail()
    lines += rep.scaling_table()
    lines += ["Headline (also printed by `scripts/demo`):", "", "```"] + rep.headline() + ["```",
                                                                                           "", END]
    return lines


def synthetic_rows():
    rows = {}
    specs = ["bvh:pbinned,max_leaf=4,bins=16,ct=1,ci=1,threads=0",
             "bvh:pair,from=pbinned,max_leaf=4,bins=16,ct=1,ci=1,threads=0", "embree:medium",
             "embree:high"]
    for i, a in enumerate(specs):
        for scene in ("flake_meshfloor2", "flake_spheres2"):
            for k in KINDS:
                for t in (1, 2):
                    rows[f"targets/trace/{a}/default/plain/{scene}/{k}/threads:{t}"] = {
                        "rays/s": 1e6 * (i + 1) * t, "nodes/ray": 30.0, "prims/ray": 4.0,
                        "bytes/prim": 40.0, "leaf_bytes/prim": 40.0}
                rows[f"targets/trace/{a}/watertight/robust/{scene}/{k}/threads:1"] = {
                    "rays/s": 0.9e6 * (i + 1)}
        for t in (1, 2):
            rows[f"targets/build/{a}/flake_meshfloor2/threads:{t}"] = {"build_ms": 100.0 / t}
    rows["targets/paired/" + specs[1] + "/default/plain/flake_meshfloor2/primary/threads:1"] = {
        "ratio": 0.52, "ratio_q1": 0.51, "ratio_q3": 0.54, "pairs": 7, "repetitions": 3,
        "aggregates": {"min": {"ratio": 0.5}, "max": {"ratio": 0.55}}}
    rows["targets/paired_build/" + specs[0] + "/flake_meshfloor2/threads:1"] = {
        "ratio": 1.04, "ratio_q1": 1.02, "ratio_q3": 1.06, "pairs": 5, "repetitions": 3,
        "aggregates": {"min": {"ratio": 1.01}, "max": {"ratio": 1.08}}}
    rows["targets/scaling/" + specs[0] + "/build/flake_meshfloor2/threads:2"] = {
        "ratio": 1.83, "ratio_q1": 1.79, "ratio_q3": 1.9, "pairs": 7, "repetitions": 3,
        "aggregates": {"min": {"ratio": 1.81}, "max": {"ratio": 1.95}}}
    rows["targets/scaling/embree:medium/shadow/flake_meshfloor2/threads:2"] = {
        "ratio": 1.7, "ratio_q1": 1.6, "ratio_q3": 1.75, "pairs": 7, "repetitions": 3,
        "aggregates": {"min": {"ratio": 1.45}, "max": {"ratio": 1.85}}}
    return rows
