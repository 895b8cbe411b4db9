"""Helpers of bench/report.py: provenance (command, git revision, compiler, CPU), reading
Google Benchmark JSON rows, number formatting, output files, the throughput bar chart and the
Pareto plot."""

import itertools
import math
import os
import platform
import re
import subprocess
import sys
import time


def import_pyplot():
    """matplotlib with the Agg backend; falls back to Debian's dist-packages (python3-matplotlib)
    when the python3 on PATH is not the system one."""
    try:
        import matplotlib
    except ImportError:
        sys.path.append("/usr/lib/python3/dist-packages")
        import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


# ---------------------------------------------------------------------------------------------
# Output files: as rtlab's (base/atomic_file.h, docs/reliability.md), written completely or not at
# all and never through a symbolic link or over a special file (the reports run as root on shared
# machines). Unlike rtlab, they replace regular files they did not write: regenerating the
# checked-in docs/results.md and its plots is their job.

_tmp_counter = itertools.count()


def replace_file(path, write):
    """Calls write(tmp) with a new temporary beside `path` (same extension, for writers that pick
    the format by it) and renames it over `path`; exits with one line naming `path` when it is a
    symbolic link or exists and is not a regular file. The temporary is removed on any error."""
    if os.path.islink(path):
        sys.exit(f"report: {path}: is a symbolic link; the report does not write through links")
    if os.path.exists(path) and not os.path.isfile(path):
        sys.exit(f"report: {path}: exists and is not a regular file")
    folder, name = os.path.split(os.path.abspath(path))
    stem, ext = os.path.splitext(name)
    while True:
        tmp = os.path.join(folder, f".{stem}.rtlab-tmp-{os.getpid()}-{next(_tmp_counter)}{ext}")
        try:
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
            break
        except FileExistsError:
            continue
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def write_text(path, text):
    """Writes `text` to `path` through replace_file."""
    def write(tmp):
        with open(tmp, "w") as f:
            f.write(text)
    replace_file(path, write)


def save_figure(fig, path):
    """fig.savefig(path) through replace_file."""
    replace_file(path, fig.savefig)


# ---------------------------------------------------------------------------------------------
# Provenance


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
        out = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return (out + ("+dirty" if dirty else "")) if out else "unknown"
    except OSError:
        return "unknown"


def compiler_name(context):
    for key in ("compiler", "cxx_compiler", "compiler_version"):
        if context.get(key):
            return str(context[key])
    try:
        out = subprocess.run(["c++", "--version"], capture_output=True, text=True).stdout
        return out.splitlines()[0].strip() if out else "unknown"
    except OSError:
        return "unknown"


def provenance(context, command, root):
    cpu = context.get("cpu") or context.get("cpu_model") or cpu_name()
    ncpu = context.get("num_cpus")
    if ncpu:
        cpu = f"{cpu} ({ncpu} cores)"
    return {
        "command": command,
        "git": context.get("git_sha") or context.get("git") or git_rev(root),
        "compiler": compiler_name(context),
        "cpu": cpu,
        "date": context.get("date", time.strftime("%Y-%m-%d %H:%M:%S")),
        "build": context.get("library_build_type", "?"),
    }


def prov_line(p):
    return (f"Command: `{p['command']}`; git {p['git']}; compiler: {p['compiler']}; "
            f"CPU: {p['cpu']}; run {p['date']}.")


def prov_caption(p):
    return f"{p['command']}\ngit {p['git']} | {p['compiler']} | {p['cpu']} | {p['date']}"


# ---------------------------------------------------------------------------------------------
# Loading benchmark JSON


def to_ms(value, unit):
    return value * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}.get(unit, 1.0)


# Suffixes Google Benchmark appends to a registered name for its run options.
RUN_OPTION = re.compile(r"/(min_time|min_warmup_time|iterations|repeats):[^/]*|"
                        r"/(manual_time|real_time|process_time)(?=/|$)")


def base_name(name):
    """The registered name without the run-option suffixes (min_time:0.010, manual_time, ...)."""
    return RUN_OPTION.sub("", name)


def load_rows(data):
    """One row per benchmark name: the median aggregate when repetitions ran, else the first
    iteration row. Counters are top-level keys of each entry in Google Benchmark's JSON. A median
    row holds the name's other aggregates (mean, stddev, min, max, ...) under "aggregates"."""
    rows, aggregates = {}, {}
    for b in data.get("benchmarks", []):
        if b.get("error_occurred"):
            continue
        name = base_name(b.get("run_name") or b["name"])
        if b.get("run_type") == "aggregate":
            aggregates.setdefault(name, {})[b.get("aggregate_name")] = b
        elif name not in rows:
            rows[name] = b
    for name, aggs in aggregates.items():
        if "median" in aggs:
            rows[name] = dict(aggs["median"], aggregates=aggs)
    return rows


def num(row, key):
    v = row.get(key)
    if v is None:
        return None
    try:
        v = float(v)
    except (TypeError, ValueError):
        return None
    return None if math.isnan(v) else v


def fmt(v, digits=3):
    if v is None:
        return "-"
    if v == 0:
        return "0"
    if abs(v) >= 1000 or abs(v) < 1e-2:
        return f"{v:.2e}"
    return f"{v:.{digits}g}"


def fmt_rate(v):
    if v is None:
        return "-"
    return "0" if v == 0 else f"{100 * v:.3g}%"


# ---------------------------------------------------------------------------------------------
# Plot helpers


def pareto_front(points):
    """Indices of the points no other point beats in both x and y (lower is better)."""
    front = []
    for i, (x, y) in enumerate(points):
        dominated = any((x2 <= x and y2 <= y) and (x2 < x or y2 < y)
                        for j, (x2, y2) in enumerate(points) if j != i)
        if not dominated:
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def plain_log_axis(ax, axis="x"):
    """Log axis labelled with plain numbers (10, 20, 50) instead of 1.2 x 10^1."""
    from matplotlib.ticker import FuncFormatter, LogLocator
    target = ax.xaxis if axis == "x" else ax.yaxis
    target.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    target.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    target.set_minor_formatter(FuncFormatter(lambda v, _: ""))


def throughput_bars(plt, path, kinds, series, title, caption, bottom):
    """Mrays/s bars grouped by ray kind, one bar per (label, values, bar style) in series, the
    legend below and the caption under it (bottom: the figure fraction kept for both)."""
    fig, ax = plt.subplots(figsize=(10.5, 4.8 + 0.22 * ((len(series) + 1) // 2)), dpi=110)
    width = 0.8 / max(1, len(series))
    for i, (label, vals, style) in enumerate(series):
        xs = [ki + (i - (len(series) - 1) / 2) * width for ki in range(len(kinds))]
        ax.bar(xs, vals, width * 0.95, label=label, edgecolor="black", linewidth=0.5, **style)
    ax.set_xticks(range(len(kinds)))
    ax.set_xticklabels(kinds)
    ax.set_ylabel("Mrays/s")
    ax.set_title(title)
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.08))
    fig.text(0.01, 0.005, caption, fontsize=7, color="dimgrey")
    fig.tight_layout(rect=(0, bottom, 1, 1))
    save_figure(fig, path)
    plt.close(fig)


def pareto_plot(plt, path, title, xlabel, ylabel, labels, xs, ys, caption, zero_floor):
    """Scatter of labelled points with the Pareto front drawn as a step line. y uses a log axis;
    y = 0 is drawn at zero_floor (below every non-zero value) and labelled "0"."""
    fig, ax = plt.subplots(figsize=(8.5, 5.5), dpi=110)
    ys_plot = [zero_floor if y == 0 else y for y in ys]
    pts = list(zip(xs, ys_plot))
    front = pareto_front(pts)
    methods = sorted({lab.rsplit(" ", 1)[0] for lab in labels})
    cmap = plt.get_cmap("tab10")
    color = {m: cmap(i % 10) for i, m in enumerate(methods)}
    for i, lab in enumerate(labels):
        method, prec = lab.rsplit(" ", 1)
        on_front = i in front
        ax.scatter(xs[i], ys_plot[i], s=90 if on_front else 45, color=color[method],
                   marker="o" if prec == "float" else "s",
                   edgecolors="black" if on_front else "none", linewidths=1.2, zorder=3,
                   label=None)
    # Labels: points that coincide on the plot share one label; alternate offsets so
    # neighbours overlap less.
    groups = []
    for i in sorted(range(len(labels)), key=lambda i: (xs[i], ys_plot[i])):
        for g in groups:
            j = g[0]
            if (abs(math.log10(xs[i] / xs[j])) < 0.02
                    and abs(math.log10(ys_plot[i] / ys_plot[j])) < 0.06):
                g.append(i)
                break
        else:
            groups.append([i])
    placed = []  # (log x, log y, dy) of the labels so far
    for g in groups:
        text = " / ".join(labels[i] for i in g)
        lx, ly = math.log10(xs[g[0]]), math.log10(ys_plot[g[0]])
        # First vertical offset whose label does not collide with a near one (same band).
        for dy in (8, -12, 22, -26, 36):
            if not any(abs(lx - px) < 0.3 and abs(ly - py) < 0.15 and pdy == dy
                       for px, py, pdy in placed):
                break
        placed.append((lx, ly, dy))
        ax.annotate(text, (xs[g[0]], ys_plot[g[0]]), textcoords="offset points", xytext=(6, dy),
                    fontsize=8, zorder=4)
    if len(front) > 1:
        fx = [pts[i][0] for i in front]
        fy = [pts[i][1] for i in front]
        ax.step(fx, fy, where="post", color="black", linestyle="--", linewidth=1, zorder=2,
                label="Pareto front")
    elif front:
        ax.scatter([], [], color="none", edgecolors="black", label="Pareto front (outlined)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log_axis(ax, "x")
    if math.log10(max(ys_plot) / min(ys_plot)) < 2.5:
        plain_log_axis(ax, "y")  # few decades: label 1, 2, 5 steps so the axis reads
    ax.margins(x=0.18, y=0.12)
    if any(y == 0 for y in ys):
        ax.axhline(zero_floor, color="grey", linewidth=0.6, linestyle=":", zorder=1)
        ax.text(0.005, zero_floor, "0 (no failure)", transform=ax.get_yaxis_transform(),
                ha="left", va="bottom", fontsize=8, color="grey")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="major", alpha=0.3)
    # Legend: colours = methods, marker = precision, outline = Pareto front.
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], marker="o", linestyle="", color=color[m], label=m) for m in methods]
    handles += [Line2D([], [], marker="o", linestyle="", color="grey", label="float"),
                Line2D([], [], marker="s", linestyle="", color="grey", label="double"),
                Line2D([], [], marker="o", linestyle="--", color="black", markerfacecolor="white",
                       label="Pareto front")]
    ax.legend(handles=handles, fontsize=8, loc="best", framealpha=0.85)
    fig.text(0.01, 0.005, caption, fontsize=7, color="dimgrey")
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    save_figure(fig, path)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------
# Sections
