"""pvpython image regression through paraview.smtesting: the alpha shape of the bundled cloud
(the trefoil knot's tube emerges from the points), coloured by the points' Elevation.

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

reader = XMLPolyDataReader(FileName=[os.path.join(data, "points.vtp")])
shape = FastDelaunay3D(Input=reader, Alpha=0.12)
view = CreateView("RenderView")
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
display = Show(shape, view)
ColorBy(display, ("POINTS", "Elevation"))
display.RescaleTransferFunctionToDataRange(True)
view.CameraPosition = [0, 0, 12]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
view.ResetCamera()
Render(view)
if not smtesting.DoRegressionTesting(view.SMProxy):
    raise RuntimeError("image comparison failed")
print("TestImage: OK")
