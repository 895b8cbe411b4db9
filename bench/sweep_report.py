"""The report of a merged sweep table (`rtlab sweep merge DIR -o T` writes T.json), used by
`bench/report.py --sweep T.json`: per scene a table (Mrays/s, nodes/ray and prims/ray per ray
kind, build ms, bytes/prim, SAH cost) and a throughput bar plot; per parameter that varies with
the other parameters of its structure fixed, line plots of Mrays/s and SAH cost against it; the
failed and missing cases; the renders (table with image links) and the cross-checks (agreement
table and error against run time per primitive kind). Every table and plot names the sweep, git revision, build, compiler,
host and CPU from the results' provenance.
"""
import os
import re

from report_common import fmt, save_figure, throughput_bars

TIMED = "mrays_per_s"


def _safe(text):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text)


def _prov(cases, table_path):
    p = next((c.get("provenance", {}) for c in cases if c.get("provenance")), {})
    hosts = sorted({c.get("provenance", {}).get("host", "?") for c in cases})
    return {
        "command": f"rtlab sweep merge; python3 bench/report.py --sweep {table_path}",
        "git": p.get("git", "?"),
        "compiler": f"{p.get('compiler', '?')} ({p.get('build', '?')} build)",
        "cpu": p.get("cpu", "?"),
        "hosts": ", ".join(hosts),
        "date": p.get("start", "?"),
    }


def _caption(prov):
    return (f"{prov['command']}\ngit {prov['git']} | {prov['compiler']} | {prov['cpu']} | "
            f"hosts {prov['hosts']} | {prov['date']}")


def _row_label(c, show_methods, show_threads):
    label = c["spec"]
    if show_methods:
        label += f" [{c['methods']}]"
    if show_threads:
        label += f" threads={c['threads']}"
    return label


def _scene_section(lines, plt, plots, scene, cases, prov):
    kinds = []
    for c in cases:
        if c["kind"] not in kinds:
            kinds.append(c["kind"])
    show_methods = len({c["methods"] for c in cases}) > 1
    show_threads = len({c["threads"] for c in cases}) > 1
    rows = {}
    for c in cases:
        rows.setdefault(_row_label(c, show_methods, show_threads), {})[c["kind"]] = c
    prims = next((c.get("primitives") for c in cases if c.get("primitives")), "?")
    rays = cases[0].get("ray_count", "?")
    lines += [f"### {scene}", "",
              f"{prims} primitives; {rays} rays per kind, median of {cases[0].get('repeat', '?')} "
              "runs; shadow rays are any-hit queries.", "",
              "| structure | " + " | ".join(f"Mrays/s {k}" for k in kinds) + " | "
              + " | ".join(f"nodes/ray {k} | prims/ray {k}" for k in kinds)
              + " | build ms | bytes/prim | SAH cost |",
              "|---|" + "---:|" * (3 * len(kinds) + 3)]
    for label, ks in rows.items():
        first = next((c for c in ks.values() if c["status"] == "done"), None)

        def cell(k, key):
            c = ks.get(k)
            if c is None:
                return "-"
            return "failed" if c["status"] != "done" else fmt(c.get(key))
        lines.append(f"| {label} | " + " | ".join(cell(k, TIMED) for k in kinds) + " | "
                     + " | ".join(f"{cell(k, 'nodes_per_ray')} | {cell(k, 'prims_per_ray')}"
                                  for k in kinds)
                     + f" | {fmt(first.get('build_ms')) if first else '-'}"
                     + f" | {fmt(first.get('bytes_per_prim')) if first else '-'}"
                     + f" | {fmt(first.get('sah_cost')) if first else '-'} |")
    lines.append("")
    if plt is None:
        return
    cmap = plt.get_cmap("tab20")
    series = [(label, [rows[label][k].get(TIMED) or 0 if k in rows[label] else 0 for k in kinds],
               {"color": cmap(i % 20)}) for i, label in enumerate(rows)]
    path = os.path.join(plots, f"sweep-mrays-{_safe(scene)}.png")
    throughput_bars(plt, path, kinds, series, f"Traversal throughput, {scene}", _caption(prov),
                    0.07)
    lines += [f"![Mrays/s, {scene}]({path})", ""]


def parameter_sweeps(cases):
    """(structure, key, fixed) -> {value: [cases]} for every numeric parameter that takes two or
    more values while the structure's other parameters stay fixed."""
    out = {}
    for c in cases:
        params = c.get("params") or {}
        for key, value in params.items():
            if not isinstance(value, (int, float)):
                continue
            fixed = tuple(sorted((k, v) for k, v in params.items() if k != key))
            out.setdefault((c["structure"], key, fixed), {}).setdefault(value, []).append(c)
    return {k: v for k, v in out.items() if len(v) >= 2}


def _sweep_section(lines, plt, plots, cases, prov):
    sweeps = parameter_sweeps([c for c in cases if c["status"] == "done"])
    if not sweeps:
        return
    lines += ["## Parameter sweeps", ""]
    for (structure, key, fixed), by_value in sorted(sweeps.items(), key=lambda x: x[0][:2]):
        xs = sorted(by_value)
        fixed_text = ",".join(f"{k}={v}" for k, v in fixed)
        lines += [f"### {structure}: {key} ({fixed_text})", "",
                  "| scene | kind | " + " | ".join(f"{key}={x}" for x in xs) + " |",
                  "|---|---|" + "---:|" * len(xs)]
        series = {}
        for x in xs:
            for c in by_value[x]:
                series.setdefault((c["scene"], c["kind"], c["methods"], c["threads"]), {})[x] = c
        for (scene, kind, methods, threads), pts in series.items():
            lines.append(f"| {scene} | {kind} | " + " | ".join(
                f"{fmt(pts[x].get(TIMED))} Mrays/s, SAH {fmt(pts[x].get('sah_cost'))}"
                if x in pts else "-" for x in xs) + " |")
        lines.append("")
        if plt is None:
            continue
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.4), dpi=110)
        for (scene, kind, methods, threads), pts in series.items():
            px = [x for x in xs if x in pts]
            ax1.plot(px, [pts[x].get(TIMED) for x in px], marker="o",
                     label=f"{scene} {kind}" + ("" if methods == "default" else f" [{methods}]"))
        scenes = {}
        for (scene, kind, methods, threads), pts in series.items():
            scenes.setdefault(scene, pts)
        for scene, pts in scenes.items():
            px = [x for x in xs if x in pts]
            ax2.plot(px, [pts[x].get("sah_cost") for x in px], marker="s", label=scene)
        for ax, ylabel in ((ax1, "Mrays/s"), (ax2, "SAH cost")):
            ax.set_xlabel(key)
            ax.set_ylabel(ylabel)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7)
            if all(isinstance(x, int) for x in xs) and min(xs) > 0 and max(xs) / min(xs) >= 8:
                ax.set_xscale("log", base=2)
                ax.set_xticks(xs)
                ax.set_xticklabels([str(x) for x in xs])
        fig.suptitle(f"{structure}: Mrays/s and SAH cost against {key} ({fixed_text})",
                     fontsize=10)
        fig.text(0.01, 0.005, _caption(prov), fontsize=7, color="dimgrey")
        fig.tight_layout(rect=(0, 0.07, 1, 0.95))
        path = os.path.join(plots, f"sweep-{_safe(structure)}-{_safe(key)}.png")
        save_figure(fig, path)
        plt.close(fig)
        lines += [f"![{structure}: {key}]({path})", ""]


def _render_section(lines, cases, table_path):
    renders = [c for c in cases if c.get("type") == "render"]
    if not renders:
        return
    folder = os.path.dirname(table_path) or "."
    lines += ["## Renders", "",
              "One render per scene, structure and AOV; Mrays/s over every ray the renderer "
              "traced (eye, shadow, reflected, refracted); render time excludes the build; "
              "`image_hash` is the same on every machine and thread count for the same image.", "",
              "| scene | structure | aov | size | rays | Mrays/s | render ms | build ms | image |",
              "|---|---|---|---|---|---|---|---|---|"]
    for c in renders:
        if c["status"] != "done":
            lines.append(f"| {c['scene']} | `{c['spec']}` | {c['kind']} | | | failed | | | |")
            continue
        img = os.path.join(folder, c["image"])
        lines.append(f"| {c['scene']} | `{c['spec']}` | {c['kind']} | {c['width']}x{c['height']} | "
                     f"{c['rays']} | {fmt(c['mrays_per_s'])} | {fmt(c['render_ms'])} | "
                     f"{fmt(c['build_ms'])} | [{c['image_hash']}]({img}) |")
    lines.append("")


def _crosscheck_section(lines, plt, plots, cases, prov):
    xs = [c for c in cases if c.get("type") == "crosscheck"]
    if not xs:
        return
    lines += ["## Cross-checks against the exact oracle", "",
              "One row per method and precision (`rtlab crosscheck`): rays whose answer is the "
              "exact one (CGAL: same hit/miss and, for hits, t within the stated relative "
              "tolerance), hits with t beyond it (wrong surface), false hits and misses, relative "
              "error of t over rays both call a hit, ns per test (single thread, set-up "
              "excluded).", "",
              "| prim | method | precision | rays | agree | wrong t | false hit | false miss | "
              "max rel t | median rel t | ns/test |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in xs:
        if c["status"] != "done":
            lines.append(f"| {c['prim']} | {c['methods']} | {c['kind']} | failed: "
                         f"{c.get('error', '?')} | | | | | | | |")
            continue
        lines.append(f"| {c['prim']} | {c['methods']} | {c['kind']} | {c['rays']} | {c['agree']} | "
                     f"{c.get('wrong_t', '-') if c.get('max_rel_t_err') is not None else '-'} | "
                     f"{c['false_hit']} | {c['false_miss']} | {fmt(c.get('max_rel_t_err'))} | "
                     f"{fmt(c.get('median_rel_t_err'))} | {fmt(c['ns_per_test'])} |")
    lines.append("")
    if not plots or plt is None:
        return
    for prim in sorted({c["prim"] for c in xs}):
        done = [c for c in xs if c["prim"] == prim and c["status"] == "done"]
        if not done:
            continue
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        for i, c in enumerate(done):
            wrong = (c["rays"] - c["agree"]) / c["rays"]
            ax.scatter(c["ns_per_test"], max(wrong, 1e-7),
                       marker="o" if c["kind"] == "float" else "s")
            # Alternate label sides so neighbouring points (float and double) stay readable.
            ax.annotate(f"{c['methods']} ({c['kind']})", (c["ns_per_test"], max(wrong, 1e-7)),
                        fontsize=7, xytext=(4, 4 if i % 2 == 0 else -10),
                        textcoords="offset points")
        ax.set_yscale("log")
        ax.set_xlabel("ns per test")
        ax.set_ylabel("rays disagreeing with the oracle\n(fraction; none drawn at 1e-7)")
        ax.set_title(f"{prim}: error against run time")
        fig.text(0.01, 0.01, _caption(prov), fontsize=6)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        path = os.path.join(plots, f"sweep-crosscheck-{_safe(prim)}.png")
        save_figure(fig, path)
        plt.close(fig)
        lines += [f"![{prim}: error against run time]({path})", ""]


def sweep_report(table, table_path, plots, plt, title=None):
    """Markdown of a merged sweep table (dict from T.json); plots go to `plots` (plt may be None
    for tables only)."""
    cases = table["cases"]
    prov = _prov(cases, table_path)
    counts = table.get("counts", {})
    lines = [f"## {title or 'Sweep ' + repr(table.get('sweep', '?'))}", "",
             f"{counts.get('done', '?')} of {counts.get('total', '?')} cases done, "
             f"{counts.get('failed', 0)} failed, {counts.get('missing', 0)} missing. "
             f"Command: `{prov['command']}`; git {prov['git']}; {prov['compiler']}; "
             f"CPU: {prov['cpu']}; hosts: {prov['hosts']}; started {prov['date']}.", ""]
    if plots and plt is not None:
        os.makedirs(plots, exist_ok=True)
    traces = [c for c in cases if c.get("type", "trace") == "trace"]
    scenes = {}
    for c in traces:
        scenes.setdefault(c["scene"], []).append(c)
    for scene, sc in scenes.items():
        _scene_section(lines, plt, plots, scene, sc, prov)
    _sweep_section(lines, plt, plots, traces, prov)
    _render_section(lines, cases, table_path)
    _crosscheck_section(lines, plt, plots, cases, prov)
    failed = [c for c in cases if c["status"] != "done"]
    if failed or table.get("missing"):
        lines += ["## Failed and missing cases", ""]
        for c in failed:
            lines.append(f"- failed: `{c['case']}` {c['scene']} `{c.get('spec', c.get('prim'))}` "
                         f"[{c['methods']}] "
                         f"{c['kind']}: {c.get('error', '?')}")
        for m in table.get("missing", []):
            lines.append(f"- missing: `{m['case']}` {m.get('type', 'trace')} {m['scene']} "
                         f"`{m['spec']}` {m['kind']}")
        lines.append("")
    return "\n".join(lines)
