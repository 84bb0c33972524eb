"""Plots benchmark.csv: seconds against points, log-log, one panel per point set, one line per
method; a filled marker where the exact validator accepted the output, a cross where it rejected
it, a hollow one where it was not checked.

usage: python3 plot.py benchmark.csv benchmark.png "machine description"
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

source, target, machine = sys.argv[1:4]
rows = defaultdict(lambda: defaultdict(list))
for row in csv.DictReader(open(source)):
    if float(row["seconds"]) > 0:
        rows[row["kind"]][row["method"]].append((int(row["n"]), float(row["seconds"]), int(row["valid"])))

kinds = list(rows)
columns = min(4, len(kinds))
lines = (len(kinds) + columns - 1) // columns
figure, axes = plt.subplots(lines, columns, figsize=(4 * columns, 3.4 * lines), squeeze=False)
# One colour per method, for its line and its markers alike (matplotlib's cycle would give each
# call the next colour).
colours = {"Core": "C0", "vtkFastDelaunay3D": "C1", "vtkDelaunay3D": "C3", "CGAL": "C2", "TetGen": "C4",
           "Core-2": "C9", "CGAL-2": "C8"}
for panel, kind in zip(axes.flat, kinds):
    for method, points in rows[kind].items():
        points.sort()
        n = [p[0] for p in points]
        seconds = [p[1] for p in points]
        panel.plot(n, seconds, "-", color=colours.get(method), label=method)
        for x, y, valid in points:
            style = {1: dict(marker="o"), 0: dict(marker="x", markersize=9),
                     -1: dict(marker="o", markerfacecolor="none")}[valid]
            panel.plot([x], [y], linestyle="none", color=colours.get(method), **style)
    panel.set_xscale("log")
    panel.set_yscale("log")
    panel.set_title(kind)
    panel.set_xlabel("points")
    panel.set_ylabel("seconds")
    panel.grid(True, which="both", alpha=0.3)
for panel in list(axes.flat)[len(kinds):]:
    panel.axis("off")
axes.flat[0].legend(fontsize=8)
figure.suptitle("3D Delaunay: time against points (o valid, x invalid, hollow unchecked) - " + machine,
                fontsize=9)
figure.tight_layout()
figure.savefig(target, dpi=80)
