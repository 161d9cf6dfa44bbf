#!/usr/bin/env python3
"""The accuracy study's figures (docs/accuracy-vs-time.md), drawn from its outputs so they rerun.

    python3 tools/accuracy_figures.py --json docs/accuracy-vs-time.json \
        [--layering docs/layering-accuracy.json] [--pictures build/accuracy-pictures] [--out docs]
    python3 tools/accuracy_figures.py --json docs/accuracy-vs-time.json --markdown

writes
  OUT/accuracy-vs-time.png, .svg  one panel per knob family (error against CPU time, log axes,
                                  every point numbered and listed beside its panel with its
                                  times, the shipped setting starred, the family's Pareto front
                                  dashed, time bars from the best to the median round, error bars
                                  of one standard error where the metric has noise), then the
                                  model floors: compensation against the random walk and the
                                  layering model against the layered ground truth (when the file
                                  of `openpbr accuracy layering` exists);
  OUT/images/accuracy-<strip>.png one strip per family from `openpbr bench accuracy --pictures`:
                                  each setting, and below it |setting - reference| scaled;
  with --markdown, the per-family tables of docs/accuracy-vs-time.md on stdout instead; with
  --choose, its choose-your-setting table.
Needs matplotlib (Debian: python3-matplotlib) and numpy.
"""
import argparse
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# SVG text as text, not glyph outlines: a small file that a browser renders with its own font.
matplotlib.rcParams["svg.fonttype"] = "none"
matplotlib.rcParams["font.size"] = 9
matplotlib.rcParams["axes.titlesize"] = 10.5

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"]


def short_time(ns):
    """1234.5 -> '1.2 us', 345 -> '345 ns'."""
    if ns is None:
        return "-"
    if ns >= 1e6:
        return f"{ns / 1e6:.3g} ms"
    if ns >= 1e3:
        return f"{ns / 1e3:.3g} us"
    return f"{ns:.3g} ns"


def place_labels(ax, points, texts, fontsize=8):
    """Numbers beside points without overlaps: for each point (in order) the first of 16
    candidate offsets whose box overlaps no placed label and no point, else the least
    overlapping; a leader line joins a label placed away from its point."""
    fig = ax.figure
    fig.canvas.draw()
    to_display = ax.transData.transform
    centres = [to_display(p) for p in points]
    # A label's box in display pixels (about 0.6 em per character).
    scale = fig.dpi / 72.0
    placed = []
    radius = 4.0 * scale
    offsets = []
    for ring in (1.0, 2.2, 3.6):
        for angle in range(0, 360, 45):
            a = math.radians(angle + 22.5 * (ring > 1.5))
            offsets.append((math.cos(a) * (6 + 8 * (ring - 1)) * scale, math.sin(a) * (6 + 8 * (ring - 1)) * scale))

    def overlap(box, other):
        return max(0.0, min(box[2], other[2]) - max(box[0], other[0])) * max(0.0, min(box[3], other[3]) - max(box[1], other[1]))

    for centre, text in zip(centres, texts):
        width = (0.62 * len(text) + 0.4) * fontsize * scale
        height = 1.1 * fontsize * scale
        best = None
        for dx, dy in offsets:
            x = centre[0] + dx + (0 if dx >= 0 else -width)
            y = centre[1] + dy - height / 2
            box = (x, y, x + width, y + height)
            cost = sum(overlap(box, other) for other in placed)
            cost += sum(overlap(box, (c[0] - radius, c[1] - radius, c[0] + radius, c[1] + radius)) for c in centres)
            if best is None or cost < best[0] - 1e-9:
                best = (cost, box, dx, dy)
            if cost == 0:
                break
        _, box, dx, dy = best
        placed.append(box)
        anchor = ax.transData.inverted().transform(((box[0] + box[2]) / 2, (box[1] + box[3]) / 2))
        ax.annotate(text, xy=ax.transData.inverted().transform(centre), xytext=anchor, textcoords="data",
                    fontsize=fontsize, ha="center", va="center", fontweight="bold",
                    arrowprops=dict(arrowstyle="-", color="#888888", lw=0.5, shrinkA=0, shrinkB=3)
                    if math.hypot(dx, dy) > 9 * scale else None)


def compact(value):
    """A tick label: 350, 1.5k, 2e-05."""
    if value >= 1000:
        return f"{value / 1000:g}k"
    if value >= 0.01:
        return f"{value:g}"
    return f"{value:.0e}".replace("e-0", "e-")


def log_ticks(axis, low, high, zero_level=None):
    """Ticks at 1-2-5 multiples of powers of ten inside [low, high] (whole decades only where
    more than four decades are shown), labelled compactly; a "0" tick at zero_level."""
    decades = math.log10(high / low)
    mantissas = (1,) if decades > 4 else (1, 2, 5) if decades > 0.6 else (1, 1.5, 2, 3, 4, 5, 6, 8)
    ticks = []
    for exponent in range(math.floor(math.log10(low)) - 1, math.ceil(math.log10(high)) + 1):
        for mantissa in mantissas:
            value = mantissa * 10.0 ** exponent
            if low <= value <= high:
                ticks.append(value)
    labels = [compact(t) for t in ticks]
    if zero_level is not None:
        ticks = [zero_level] + [t for t in ticks if t > zero_level * 2.5]
        labels = ["0"] + [compact(t) for t in ticks[1:]]
    axis.set_major_locator(matplotlib.ticker.FixedLocator(ticks))
    axis.set_major_formatter(matplotlib.ticker.FixedFormatter(labels))
    axis.set_minor_locator(matplotlib.ticker.NullLocator())


def log_limits(values, pad=2.5):
    values = [v for v in values if v and v > 0 and math.isfinite(v)]
    if not values:
        return 1e-3, 1.0
    low, high = min(values), max(values)
    return low / pad, high * pad


def draw_family(ax, legend_ax, family, colour):
    settings = family["settings"]
    xs = [s["cpu_ns"]["best"] for s in settings]
    errors = [s["error"] for s in settings]
    nonzero = [e for e in errors if e > 0]
    y_low, y_high = log_limits(nonzero)
    has_zero = any(e == 0 for e in errors)
    zero_level = None
    if has_zero:
        # Exact zeros (a reference, bit-identical storage) sit on a band of their own at the
        # bottom, a decade below the smallest error.
        zero_level = y_low / 10.0
        y_low = zero_level / 2.0
        ax.axhspan(y_low, zero_level * 2.0, color="#f2f2f2", zorder=0)
    ys = [e if e > 0 else zero_level for e in errors]
    x_low, x_high = log_limits(xs + [s["cpu_ns"]["median"] for s in settings], pad=1.25)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(x_low, x_high)
    ax.set_ylim(y_low, y_high)
    log_ticks(ax.xaxis, x_low, x_high)
    log_ticks(ax.yaxis, y_low, y_high, zero_level)
    front = sorted([i for i, s in enumerate(settings) if s["pareto"]], key=lambda i: xs[i])
    if len(front) > 1:
        step_x, step_y = [], []
        for k, i in enumerate(front):
            if k:
                step_x.append(xs[i])
                step_y.append(ys[front[k - 1]])
            step_x.append(xs[i])
            step_y.append(ys[i])
        ax.plot(step_x, step_y, ls="--", color="#444444", lw=0.8, zorder=1)
    for i, s in enumerate(settings):
        median = s["cpu_ns"]["median"]
        uncertainty = s.get("error_uncertainty", 0.0)
        ax.errorbar(xs[i], ys[i], xerr=[[0], [max(median - xs[i], 0)]],
                    yerr=[[min(uncertainty, ys[i] * 0.9)], [uncertainty]] if uncertainty > 0 else None,
                    fmt="none", ecolor=colour, elinewidth=0.8, capsize=2, alpha=0.7, zorder=2)
        marker = "*" if s["shipped"] else ("D" if s["reference"] else "o")
        ax.scatter([xs[i]], [ys[i]], marker=marker, s=110 if s["shipped"] else 30,
                   facecolor=colour if (s["pareto"] or s["shipped"]) else "white", edgecolor=colour,
                   linewidth=1.2, zorder=3)
    if family["kind"] == "variance":
        # Equal efficiency with the shipped setting: variance x time constant.
        shipped = next(s for s in settings if s["shipped"])
        cost = shipped["error"] * shipped["cpu_ns"]["best"]
        line_x = np.geomspace(x_low, x_high, 20)
        ax.plot(line_x, cost / line_x, color="#999999", lw=0.7, ls=":", zorder=1)
        ax.text(x_high, cost / x_high, " equal\n efficiency", fontsize=7, color="#777777", va="center", ha="left")
    place_labels(ax, list(zip(xs, ys)), [str(i + 1) for i in range(len(settings))])
    ax.set_title(family["family"], loc="left", fontweight="bold")
    kind = family["kind"]
    ax.set_ylabel(("variance per sample" if kind == "variance" else "error") + " (log)")
    ax.set_xlabel(family["time_metric"].replace("CPU ns", "CPU ns (log)"))
    ax.grid(True, which="major", color="#eeeeee", lw=0.6)
    lines = [wrap(family["error_metric"], 80), "vs " + wrap(family["reference"], 77),
             "    setting" + " " * 30 + "error | CPU" + (" | lavapipe (lvp), WebGPU (wgpu)" if any(
                 "lavapipe_ns" in s for s in settings) else "")]
    for i, s in enumerate(settings):
        mark = "*" if s["shipped"] else " "
        extra = ""
        if kind == "variance":
            extra = f" (efficiency x{s['other_errors'].get('efficiency relative to the shipped setting', 0):.2g})"
        gpu = ""
        if "lavapipe_ns" in s:
            gpu += f" | lvp {short_time(s['lavapipe_ns']['best'])}"
        if "webgpu_ns" in s:
            gpu += f" | wgpu {short_time(s['webgpu_ns']['best'])}"
        error = "0" if s["error"] == 0 else f"{s['error']:.2g}"
        lines.append(f"{i + 1:>2}{mark} {s['setting'][:36]:<36} {error:>7}{extra} | {short_time(s['cpu_ns']['best'])}{gpu}")
    legend_ax.axis("off")
    legend_ax.text(0.0, 1.0, "\n".join(lines), va="top", ha="left", fontsize=7.2, family="monospace",
                   transform=legend_ax.transAxes)


def wrap(text, width):
    words, lines, line = text.split(), [], ""
    for word in words:
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}".strip()
    lines.append(line)
    return "\n   ".join(lines)


def draw_compensation_floor(ax, legend_ax, floor):
    rows = floor["rows"]
    xs = [r["time_ns"] for r in rows]
    ys = [r["error"] for r in rows]
    ax.set_xscale("log")
    ax.set_yscale("log")
    x_limits, y_limits = log_limits(xs, pad=1.6), log_limits(ys)
    ax.set_xlim(*x_limits)
    ax.set_ylim(*y_limits)
    log_ticks(ax.xaxis, *x_limits)
    log_ticks(ax.yaxis, *y_limits)
    for i, r in enumerate(rows):
        openpbr = r["setting"].startswith("OpenPBR")
        colour = "#1f77b4" if openpbr else "#7f7f7f"
        if r["error_uncertainty"] > 0:
            ax.errorbar(xs[i], ys[i], yerr=r["error_uncertainty"], fmt="none", ecolor=colour, elinewidth=0.8, capsize=2)
        ax.scatter([xs[i]], [ys[i]], marker="*" if "shipped" in r["setting"] else "o", s=110 if "shipped" in r["setting"] else 30,
                   color=colour, zorder=3)
    place_labels(ax, list(zip(xs, ys)), [str(i + 1) for i in range(len(rows))])
    ax.set_title("model floor: compensation vs random walk", loc="left", fontweight="bold")
    ax.set_xlabel("CPU ns per eval or look-up (log)")
    ax.set_ylabel("albedo error (log)")
    ax.grid(True, which="major", color="#eeeeee", lw=0.6)
    lines = [wrap(floor["error_metric"], 80), "vs " + wrap(floor["reference"], 77), ""]
    for i, r in enumerate(rows):
        lines.append(f"{i + 1:>2} {r['setting'][:44]}: {r['error']:.2g}; {short_time(r['time_ns'])}")
    legend_ax.axis("off")
    legend_ax.text(0.0, 1.0, "\n".join(lines), va="top", ha="left", fontsize=7.2, family="monospace",
                   transform=legend_ax.transAxes)


def layering_rows(layering):
    """Per material: the largest albedo error over channels and view cosines, the reference's
    standard error there, the model's and the reference's mean times."""
    per_material = {}
    for row in layering.get("rows", []):
        entry = per_material.setdefault(row["material"], {"error": 0.0, "se": 0.0, "model_ns": [], "reference_ns": [],
                                                          "group": row.get("group", "")})
        for c in range(3):
            error = abs(row["model_albedo"][c] - row["reference_albedo"][c])
            if error >= entry["error"]:
                entry["error"] = error
                entry["se"] = row["reference_standard_error"][c]
        entry["model_ns"].append(row.get("model_ns", 0.0))
        entry["reference_ns"].append(row.get("reference_ns", 0.0))
    return sorted(per_material.items(), key=lambda item: -item[1]["error"])


def draw_layering_floor(ax, legend_ax, layering, note):
    ax.set_title("model floor: layering vs layered ground truth", loc="left", fontweight="bold")
    legend_ax.axis("off")
    if not layering:
        ax.axis("off")
        ax.text(0.02, 0.6, wrap(note, 55), va="top", ha="left", fontsize=8, transform=ax.transAxes)
        return
    rows = layering_rows(layering)
    errors = [max(r["error"], 1e-6) for _, r in rows]
    ses = [r["se"] for _, r in rows]
    ranks = np.arange(1, len(rows) + 1)
    ax.set_yscale("log")
    groups = sorted({r["group"] for _, r in rows})
    for k, group in enumerate(groups):
        members = [i for i, (_, r) in enumerate(rows) if r["group"] == group]
        ax.errorbar(ranks[members], [errors[i] for i in members],
                    yerr=[[min(ses[i], errors[i] * 0.9) for i in members], [ses[i] for i in members]], fmt="o", ms=3,
                    color=COLOURS[k % len(COLOURS)], ecolor="#bbbbbb", elinewidth=0.8, capsize=1.5,
                    label=group or None)
    if len(groups) > 1:
        ax.legend(fontsize=7, loc="upper right")
    ax.set_xlabel("material (bundled and grid), by error")
    ax.set_ylabel("albedo error (log)")
    ax.grid(True, which="major", color="#eeeeee", lw=0.6)
    shown = min(8, len(rows))
    place_labels(ax, list(zip(ranks[:shown], errors[:shown])), [str(i + 1) for i in range(shown)])
    model_ns = [np.mean(r["model_ns"]) for _, r in rows]
    summary = layering.get("summary", {})
    if "median_reference_estimate_ms" in summary:
        truth = f"the ground truth {short_time(summary['median_reference_estimate_ms'] * 1e6)} per estimate"
    else:
        truth = f"the ground truth {short_time(np.median([np.mean(r['reference_ns']) for _, r in rows]))}"
    lines = ["directional albedo error vs the layered ground truth",
             "(max over channels and view cosines; bars: one standard error)",
             f"the model {short_time(np.median(model_ns))} per prepare+eval, {truth} (medians)", ""]
    for i, (material, r) in enumerate(rows[:shown]):
        group = f" [{r['group']}]" if r["group"] else ""
        lines.append(f"{i + 1:>2} {(material + group)[:48]:<48} {r['error']:.2g} +- {r['se']:.1g}")
    if len(rows) > shown:
        lines.append(f"   ... {len(rows) - shown} more, down to {rows[-1][1]['error']:.2g}")
    legend_ax.text(0.0, 1.0, "\n".join(lines), va="top", ha="left", fontsize=7.2, family="monospace",
                   transform=legend_ax.transAxes)


def draw_figure(study, layering, out):
    families = study["families"]
    floors = study.get("model_floors", {})
    panels = len(families) + 2
    columns = 3
    rows = math.ceil(panels / columns)
    fig = plt.figure(figsize=(columns * 6.0, rows * 5.6))
    grid = fig.add_gridspec(rows * 2, columns, height_ratios=[3.0, 1.75] * rows, hspace=0.42, wspace=0.26,
                            left=0.045, right=0.985, top=0.945, bottom=0.015)
    for index in range(panels):
        r, c = divmod(index, columns)
        ax = fig.add_subplot(grid[2 * r, c])
        legend_ax = fig.add_subplot(grid[2 * r + 1, c])
        if index < len(families):
            draw_family(ax, legend_ax, families[index], COLOURS[index % len(COLOURS)])
        elif index == len(families):
            draw_compensation_floor(ax, legend_ax, floors["compensation"])
        else:
            note = floors.get("layering", {}).get("note", "docs/layering-accuracy.json absent")
            draw_layering_floor(ax, legend_ax, layering, note)
    run = study.get("run", {})
    fig.suptitle("OpenPBR: what each accuracy knob gets wrong (its own metric, against its own reference) and what "
                 f"it costs (openpbr bench accuracy, {run.get('date', '')})\n"
                 "star: shipped setting; filled: on the family's Pareto front (dashed); diamond: the reference; "
                 "horizontal bars: best to median CPU time over the rounds; vertical bars: one standard error",
                 fontsize=11, x=0.045, y=0.995, ha="left", va="top")
    fig.savefig(os.path.join(out, "accuracy-vs-time.png"), dpi=80)
    fig.savefig(os.path.join(out, "accuracy-vs-time.svg"))
    plt.close(fig)


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def nice_scale(largest):
    """A 1-2-5 factor that maps `largest` to at most 1."""
    if largest <= 0:
        return 1.0
    exponent = math.floor(math.log10(1.0 / largest))
    for mantissa in (5, 2, 1):
        if mantissa * 10 ** exponent * largest <= 1.0:
            return mantissa * 10 ** exponent
    return 10 ** exponent


def draw_strip(manifest_dir, strip, out):
    w, h = strip["width"], strip["height"]

    def load(name):
        return np.fromfile(os.path.join(manifest_dir, name), dtype="<f4").reshape(h, w, 3)

    tiles = strip["tiles"]
    images = [load(t["file"]) for t in tiles]
    inside = images[0][..., 0] >= 0
    if "converged" in strip:
        reference = load(strip["converged"]["file"])
        reference_label = strip["converged"]["setting"]
    else:
        reference = images[[t["reference"] for t in tiles].index(True)]
        reference_label = None
    exposure = 0.85 / max(np.percentile(reference[inside], 99.5), 1e-6)
    differences = [np.where(inside[..., None], np.abs(image - reference), 0.0) for image in images]
    columns = len(tiles) + (1 if reference_label else 0)
    # A variance knob's noise images share one scale (their noise is what is compared); a bias
    # knob's each get their own, so a small difference is seen as well as a large one.
    common_scale = nice_scale(max(float(d.max()) for d in differences)) if reference_label else None
    width = max(columns * 1.45, 4.4)
    fig, axes = plt.subplots(2, columns, figsize=(width, 3.45), squeeze=False)
    column = 0
    if reference_label:
        axes[0][0].imshow(np.where(inside[..., None], srgb(reference * exposure), 0.5), interpolation="nearest")
        axes[0][0].set_title(reference_label, fontsize=6.5)
        axes[1][0].text(0.5, 0.5, "reference", ha="center", va="center", fontsize=7, transform=axes[1][0].transAxes)
        column = 1
    for tile, image, difference in zip(tiles, images, differences):
        top, bottom = axes[0][column], axes[1][column]
        top.imshow(np.where(inside[..., None], srgb(image * exposure), 0.5), interpolation="nearest")
        top.set_title(tile["setting"], fontsize=6.5)
        if tile["reference"] and not reference_label:
            bottom.text(0.5, 0.5, "reference", ha="center", va="center", fontsize=7, transform=bottom.transAxes)
        else:
            peak = float(difference.max())
            scale = common_scale or nice_scale(peak)
            bottom.imshow(srgb(difference * scale), interpolation="nearest")
            if common_scale:
                rms = float(np.sqrt(np.mean(np.square(difference[inside]))))
                bottom.set_title(f"x{scale:g} (rms {rms:.2g})", fontsize=6.5)
            else:
                bottom.set_title("identical" if peak == 0 else f"x{scale:g} (max {peak:.2g})", fontsize=6.5)
        column += 1
    for ax in axes.flat:
        ax.set_xticks([])
        ax.set_yticks([])
        for spine in ax.spines.values():
            spine.set_visible(False)
    title = f"{strip['family']}: {strip['material']}; {strip['quantity']}; below: |setting - reference|, scaled"
    fig.suptitle(wrap(title, int(width * 15)).replace("\n   ", "\n"), fontsize=7)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.78, bottom=0.02, wspace=0.05, hspace=0.25)
    fig.savefig(os.path.join(out, "images", f"accuracy-{strip['name'].replace('_', '-')}.png"), dpi=110)
    plt.close(fig)


FLOOR_ROWS = 16  # rows of a model floor in the Markdown tables, e.g. 16


def markdown_tables(study):
    """Per family a Markdown table: setting, its error, its other metrics' headline, CPU time (best
    and median), lavapipe and WebGPU device times; then the model floors."""
    out = []
    for family in study["families"]:
        out.append(f"**{family['family']}** ({family['kind']}): {family['error_metric']}; against {family['reference']}. "
                   f"Time: {family['time_metric']}.\n")
        out.append("| setting | error | other metrics | CPU ns (best / median) | lavapipe ns | WebGPU ns |")
        out.append("| --- | --- | --- | --- | --- | --- |")
        for s in family["settings"]:
            name = s["setting"] + (" **(shipped)**" if s["shipped"] and "shipped" not in s["setting"] else "")
            others = "; ".join(f"{k} {v:.3g}" for k, v in s["other_errors"].items())
            gpu = [f"{s[k]['best']:.4g}" if k in s else "-" for k in ("lavapipe_ns", "webgpu_ns")]
            out.append(f"| {name} | {s['error']:.3g} | {others} | {s['cpu_ns']['best']:.4g} / {s['cpu_ns']['median']:.4g} | "
                       f"{gpu[0]} | {gpu[1]} |")
        out.append("")
    for name, floor in study.get("model_floors", {}).items():
        out.append(f"**model floor, {name}**: {floor['error_metric']}; against {floor['reference']}.\n")
        if floor.get("note"):
            out.append(floor["note"] + "\n")
            continue
        out.append("| model | error | standard error | ns |")
        out.append("| --- | --- | --- | --- |")
        # The largest errors first; a long floor (the layering file's materials) cut to its worst
        # FLOOR_ROWS with the count and range of the rest.
        rows = sorted(floor["rows"], key=lambda r: -r["error"]) if len(floor["rows"]) > FLOOR_ROWS else floor["rows"]
        for r in rows[:FLOOR_ROWS]:
            out.append(f"| {r['setting']} | {r['error']:.3g} | {r['error_uncertainty']:.2g} | {r['time_ns']:.4g} |")
        if len(rows) > FLOOR_ROWS:
            rest = rows[FLOOR_ROWS:]
            out.append(f"| {len(rest)} more | {rest[-1]['error']:.2g} - {rest[0]['error']:.2g} | | |")
        out.append("")
    return "\n".join(out)


# The choose-your-setting rule, stated in docs/accuracy-vs-time.md: real time takes, among the
# settings with a GPU kernel (all, where the family has none) whose error is at most
# REAL_TIME_ERROR, those within the run's timing noise (time_noise) of the fastest (device time on
# lavapipe where measured, else CPU), and of those the shipped one, else the least error;
# offline takes the least error (errors below EQUAL_ERROR count as equal), the shipped one among
# equals, then the faster. For the sampler (a variance knob) both take the best efficiency,
# 1 / (variance x time).
REAL_TIME_ERROR = 0.01  # 1 % (relative or absolute reflectance): about one 8-bit step at mid-grey
EQUAL_ERROR = 1e-3  # 0.1 %: below the noise of a converged offline render, e.g. 1e-3
TIME_NOISE = 0.05  # the least: settings of equal work timed within 5 % of each other (docs/accuracy-vs-time.md)


def setting_time(setting):
    return setting["lavapipe_ns"]["best"] if "lavapipe_ns" in setting else setting["cpu_ns"]["best"]


def time_noise(study):
    """How far apart one run times the same kernel: the study times the shipped kernel once per family
    that shares its workload (compensation, table storage, fast math, precision), so the spread of
    those times, (slowest - fastest) / fastest on lavapipe (CPU where no GPU time), is the run's own
    timing noise; at least TIME_NOISE. E.g. 0.126 on 2026-12-02 (896-1009 ns on lavapipe)."""
    groups = {}
    for family in study["families"]:
        for setting in family["settings"]:
            if setting["shipped"]:
                groups.setdefault((setting["variant"], family["time_metric"]), []).append(setting_time(setting))
    spreads = [max(times) / min(times) - 1.0 for times in groups.values() if len(times) > 1 and min(times) > 0]
    return max([TIME_NOISE] + spreads)


def suited_settings(family, noise=TIME_NOISE):
    """(index for real time, index for offline) of a family's settings."""
    settings = family["settings"]
    indices = range(len(settings))
    if family["kind"] == "variance":
        best = max(indices, key=lambda i: settings[i]["other_errors"].get("efficiency relative to the shipped setting", 0))
        return best, best
    offline = min(indices, key=lambda i: (max(settings[i]["error"], EQUAL_ERROR), not settings[i]["shipped"],
                                          settings[i]["cpu_ns"]["best"]))
    # Real time is on a GPU: the settings with a kernel where the family has any, timed on lavapipe.
    on_gpu = [i for i in indices if "lavapipe_ns" in settings[i]] or list(indices)
    within = [i for i in on_gpu if settings[i]["error"] <= REAL_TIME_ERROR] or [offline]
    fastest = min(setting_time(settings[i]) for i in within)
    quick = [i for i in within if setting_time(settings[i]) <= fastest * (1 + noise)]
    return min(quick, key=lambda i: (not settings[i]["shipped"], settings[i]["error"])), offline


def choose_table(study):
    """The choose-your-setting table: per knob and setting its error (the family's metric), CPU,
    lavapipe and WebGPU times, and which setting suits real time and which offline."""
    out = ["| knob | setting | error | CPU ns | lavapipe ns | WebGPU ns | suits |", "| --- | --- | --- | --- | --- | --- | --- |"]
    noise = time_noise(study)
    for family in study["families"]:
        real_time, offline = suited_settings(family, noise)
        for i, s in enumerate(family["settings"]):
            if family["kind"] == "variance":
                efficiency = s["other_errors"].get("efficiency relative to the shipped setting", 0)
                error = f"efficiency x{efficiency:.2f}"
            else:
                error = "0 (reference)" if s["reference"] else ("0" if s["error"] == 0 else f"{s['error']:.2g}")
            suits = ", ".join(name for name, index in (("real time", real_time), ("offline", offline)) if index == i)
            gpu = [f"{s[k]['best']:.0f}" if k in s else "-" for k in ("lavapipe_ns", "webgpu_ns")]
            name = s["setting"] + (" **(shipped)**" if s["shipped"] and "shipped" not in s["setting"] else "")
            out.append(f"| {family['family'] if i == 0 else ''} | {name} | {error} | {s['cpu_ns']['best']:.0f} | "
                       f"{gpu[0]} | {gpu[1]} | {suits} |")
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--json", required=True, help="the study's JSON, e.g. docs/accuracy-vs-time.json")
    parser.add_argument("--layering", help="`openpbr accuracy layering`'s JSON, e.g. docs/layering-accuracy.json")
    parser.add_argument("--pictures", help="`openpbr bench accuracy --pictures DIR`'s directory")
    parser.add_argument("--out", default="docs", help="where the figure goes (strips under OUT/images), e.g. docs")
    parser.add_argument("--markdown", action="store_true", help="print the per-family tables as Markdown and stop")
    parser.add_argument("--choose", action="store_true", help="print the choose-your-setting table as Markdown and stop")
    args = parser.parse_args()
    with open(args.json) as file:
        study = json.load(file)
    if args.markdown:
        print(markdown_tables(study))
        return 0
    if args.choose:
        print(choose_table(study))
        return 0
    layering = None
    if args.layering and os.path.exists(args.layering):
        with open(args.layering) as file:
            layering = json.load(file)
    os.makedirs(os.path.join(args.out, "images"), exist_ok=True)
    draw_figure(study, layering, args.out)
    if args.pictures:
        with open(os.path.join(args.pictures, "manifest.json")) as file:
            manifest = json.load(file)
        for strip in manifest["strips"]:
            draw_strip(args.pictures, strip, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
