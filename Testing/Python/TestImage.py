"""pvpython image regression through paraview.smtesting: the demo's picture (knot_view.py), the
alpha shape of the bundled cloud, in which the trefoil knot emerges from the points.

usage: pvpython TestImage.py <plugin .so> <Data folder> -V <absolute baseline> -T <output dir>
"""
import os
import sys

from paraview.simple import *
from paraview import smtesting

plugin, data = sys.argv[1:3]
sys.argv = [sys.argv[0]] + sys.argv[3:]
smtesting.ProcessCommandLineArguments()
LoadPlugin(plugin, remote=False, ns=globals())
from knot_view import show_knot  # noqa: E402

reader = XMLPolyDataReader(FileName=[os.path.join(data, "points.vtp")])
view = show_knot(FastDelaunay3D, reader, 400, 300)
if not smtesting.DoRegressionTesting(view.SMProxy):
    raise RuntimeError("image comparison failed")
print("TestImage: OK")
