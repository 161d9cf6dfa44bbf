#!/usr/bin/env python3
"""Plots `openpbr fit --history DIR` files: per case the loss and each fitted parameter over the
iterations, with the true values as dashed lines (docs/gradients.md, "A material fit").

Usage: plot_fit.py HISTORY_DIR OUTPUT.svg, e.g.
    build/openpbr fit examples/fit/*.json --history build/fit
    tools/plot_fit.py build/fit docs/images/material-fit.svg
Needs matplotlib (Debian: python3-matplotlib). Exit status 1 with a message when the directory
holds no history file.
"""
import csv
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


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 1
    files = sorted(pathlib.Path(sys.argv[1]).glob("*.csv"))
    if not files:
        print(f"plot_fit.py: no history file (*.csv) in {sys.argv[1]}", file=sys.stderr)
        return 1
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(len(files), 2, figsize=(11, 2.6 * len(files)), squeeze=False)
    for row, path in enumerate(files):
        names, truth, iterations, losses, values = read_history(path)
        loss_axis, value_axis = axes[row]
        loss_axis.semilogy(iterations, losses, color="black")
        loss_axis.set_title(f"{path.stem}: loss", fontsize=9)
        loss_axis.set_xlabel("iteration", fontsize=8)
        for index, name in enumerate(names):
            line = value_axis.plot(iterations, values[index], label=name, linewidth=1.2)[0]
            value_axis.axhline(truth[index], color=line.get_color(), linestyle="--", linewidth=0.8)
        value_axis.set_title(f"{path.stem}: parameters (dashed: truth)", fontsize=9)
        value_axis.set_xlabel("iteration", fontsize=8)
        value_axis.legend(fontsize=6, ncol=2, loc="best")
        for axis in (loss_axis, value_axis):
            axis.tick_params(labelsize=7)
    figure.tight_layout()
    figure.savefig(sys.argv[2], metadata={"Date": None})
    print(f"wrote {sys.argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
