"""Fast Voronoi 3D as a ParaView user runs it: pvpython, UpdatePipeline, default properties but
NumberOfThreads, on uniform points in the unit cube; with polyhedra (the default) and without, and,
where the benchmark program is given, Voro++'s volumes and neighbours on as many points in between
(Benchmark --voronoi --methods Voro++), so that every ratio comes from one run.

usage: PYTHONPATH=<build>/lib/python3.11/site-packages \\
  pvpython pvpython_voronoi.py <plugin .so> [points=1000000] [runs=3] [threads=1] [Benchmark]
prints a markdown table: each method's best and worst of the runs, the conversion's share of the
filter's time (the writing of VTK's arrays, ConversionSeconds), and Voro++'s best over each
method's best.
"""
import re
import subprocess
import sys
import time

import numpy as np

import fastdelaunay3d.FastDelaunay3DFilters  # noqa: F401 (typed client-side objects)
from paraview.simple import Delete, LoadPlugin, TrivialProducer
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData

plugin = sys.argv[1]
count = int(float(sys.argv[2])) if len(sys.argv) > 2 else 1000000
runs = int(sys.argv[3]) if len(sys.argv) > 3 else 3
threads = int(sys.argv[4]) if len(sys.argv) > 4 else 1
benchmark = sys.argv[5] if len(sys.argv) > 5 else None
LoadPlugin(plugin, remote=False, ns=globals())  # defines FastVoronoi3D

points = vtkPoints()
points.SetData(numpy_to_vtk(np.random.default_rng(1).random((count, 3)), deep=True))
cloud = vtkPolyData()
cloud.SetPoints(points)
source = TrivialProducer()
source.GetClientSideObject().SetOutput(cloud)


def filter_run(polyhedra):
    """Seconds of UpdatePipeline, and of the conversion within it."""
    voronoi = FastVoronoi3D(Input=source)  # noqa: F821 (from LoadPlugin)
    voronoi.NumberOfThreads = threads
    voronoi.GeneratePolyhedra = int(polyhedra)
    start = time.perf_counter()
    voronoi.UpdatePipeline()
    seconds = time.perf_counter() - start
    conversion = voronoi.GetClientSideObject().GetConversionSeconds()
    Delete(voronoi)
    return seconds, conversion


def voropp_run():
    """Seconds of Voro++'s volumes and neighbours, in a child process of the benchmark program."""
    out = subprocess.run([benchmark, "--voronoi", "--kinds", "cube", "--sizes", str(count),
                          "--threads", "1", "--methods", "Voro++"],
                         capture_output=True, text=True, check=True).stderr
    return float(re.search(r"Voro\+\+: ([0-9.]+) s", out).group(1)), 0.0


methods = {"filter, polyhedra": lambda: filter_run(True),
           "filter, figures": lambda: filter_run(False)}
if benchmark:
    methods["Voro++ volumes and neighbours"] = voropp_run
times = {name: [] for name in methods}
for r in range(runs):
    order = list(methods) if r % 2 == 0 else list(reversed(methods))
    for name in order:
        times[name].append(methods[name]())

voropp = min(s for s, _ in times.get("Voro++ volumes and neighbours", [(0, 0)]))
print(f"{count} uniform points, NumberOfThreads {threads}, {runs} interleaved runs\n")
print("| method | best s | worst s | conversion | Voro++ / this |")
print("|---|---:|---:|---:|---:|")
for name, values in times.items():
    best = min(values, key=lambda v: v[0])
    share = f"{best[1]:.3f} s ({100 * best[1] / best[0]:.0f}%)" if best[1] > 0 else "-"
    ratio = f"{voropp / best[0]:.2f}x" if voropp > 0 else "-"
    print(f"| {name} | {best[0]:.3f} | {max(v[0] for v in values):.3f} | {share} | {ratio} |")
