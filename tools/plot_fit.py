#!/usr/bin/env python3
"""Plots `openpbr fit --history DIR` files: per case the loss and each fitted parameter over the
iterations, with the true values as dashed lines (docs/gradients.md, "A material fit").

Usage: plot_fit.py HISTORY_DIR OUTPUT.svg, e.g.
    build/openpbr fit examples/fit/*.json --history build/fit
    tools/plot_fit.py build/fit docs/images/material-fit.svg
Writes the SVG itself (no plotting library). Exit status 1 with a message when the directory
holds no history file.
"""
import csv
import math
import pathlib
import sys


def read_history(path):
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    names = rows[0][2:]
    truth = [float(value) for value in rows[1][2:]]
    iterations = [int(row[0]) for row in rows[2:]]
    losses = [float(row[1]) for row in rows[2:]]
    values = [[float(row[2 + index]) for row in rows[2:]] for index in range(len(names))]
    return names, truth, iterations, losses, values


COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"]
PANEL_WIDTH, PANEL_HEIGHT, MARGIN = 420, 170, 40


def polyline(xs, ys, x_range, y_range, left, top, colour, dash=""):
    """One series as an SVG polyline inside the panel at (left, top)."""
    def to_x(x):
        return left + MARGIN + (x - x_range[0]) / max(x_range[1] - x_range[0], 1e-12) * (PANEL_WIDTH - 2 * MARGIN)

    def to_y(y):
        return top + PANEL_HEIGHT - MARGIN + (y_range[0] - y) / max(y_range[1] - y_range[0], 1e-12) * (PANEL_HEIGHT - 2 * MARGIN)

    points = " ".join(f"{to_x(x):.1f},{to_y(y):.1f}" for x, y in zip(xs, ys))
    dash_attribute = f' stroke-dasharray="{dash}"' if dash else ""
    return f'<polyline fill="none" stroke="{colour}" stroke-width="1.2"{dash_attribute} points="{points}"/>'


def panel_frame(left, top, title, y_range, y_label):
    """The panel's box, title and y-axis ends."""
    box = (f'<rect x="{left + MARGIN}" y="{top + MARGIN}" width="{PANEL_WIDTH - 2 * MARGIN}" '
           f'height="{PANEL_HEIGHT - 2 * MARGIN}" fill="none" stroke="#888"/>')
    text = (f'<text x="{left + MARGIN}" y="{top + MARGIN - 8}" font-size="11">{title}</text>'
            f'<text x="{left + 2}" y="{top + MARGIN + 4}" font-size="9">{y_label(y_range[1])}</text>'
            f'<text x="{left + 2}" y="{top + PANEL_HEIGHT - MARGIN}" font-size="9">{y_label(y_range[0])}</text>')
    return box + text


def svg_figure(rows):
    """Per case: the log10 of the loss, and each parameter with its truth dashed, over iterations."""
    parts = []
    for row, (name, names, truth, iterations, losses, values) in enumerate(rows):
        top = row * PANEL_HEIGHT
        x_range = (min(iterations), max(iterations))
        logs = [math.log10(max(loss, 1e-12)) for loss in losses]
        loss_range = (min(logs), max(logs))
        parts.append(panel_frame(0, top, f"{name}: loss (log10)", loss_range, lambda y: f"{y:.1f}"))
        parts.append(polyline(iterations, logs, x_range, loss_range, 0, top, "black"))
        every = [v for series in values for v in series] + truth
        value_range = (min(every), max(every))
        parts.append(panel_frame(PANEL_WIDTH, top, f"{name}: parameters (dashed: truth)", value_range, lambda y: f"{y:.2f}"))
        for index, label in enumerate(names):
            colour = COLOURS[index % len(COLOURS)]
            parts.append(polyline(iterations, values[index], x_range, value_range, PANEL_WIDTH, top, colour))
            parts.append(polyline(x_range, [truth[index]] * 2, x_range, value_range, PANEL_WIDTH, top, colour, "4 3"))
            parts.append(f'<text x="{2 * PANEL_WIDTH + 4}" y="{top + MARGIN + 11 * index}" font-size="9" '
                         f'fill="{colour}">{label}</text>')
    width, height = 2 * PANEL_WIDTH + 170, PANEL_HEIGHT * len(rows)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif">'
            f'<rect width="100%" height="100%" fill="white"/>' + "".join(parts) + "</svg>\n")


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 1
    files = sorted(pathlib.Path(sys.argv[1]).glob("*.csv"))
    if not files:
        print(f"plot_fit.py: no history file (*.csv) in {sys.argv[1]}", file=sys.stderr)
        return 1
    rows = [(path.stem, *read_history(path)) for path in files]
    pathlib.Path(sys.argv[2]).write_text(svg_figure(rows))
    print(f"wrote {sys.argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
