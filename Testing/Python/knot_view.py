"""The picture of the bundled cloud that the demo writes and pvpython.Image checks: its alpha
shape (Alpha = 0.12, between the knot's point spacing and the sparse background's), which shows
the trefoil knot the points were sampled from, coloured by the points' Elevation."""
from paraview.simple import ColorBy, CreateView, Render, Show


def show_knot(fast_delaunay_3d, points, width, height):
    """Renders the alpha shape of `points` in a new view of the given size and returns the view.
    `fast_delaunay_3d` is the FastDelaunay3D function that LoadPlugin put in the caller's namespace."""
    shape = fast_delaunay_3d(Input=points, Alpha=0.12)
    view = CreateView("RenderView")
    view.ViewSize = [width, height]
    view.OrientationAxesVisibility = 0
    display = Show(shape, view)
    ColorBy(display, ("POINTS", "Elevation"))
    display.RescaleTransferFunctionToDataRange(True)
    view.CameraPosition = [0, 0, 12]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.ResetCamera()
    Render(view)
    return view
