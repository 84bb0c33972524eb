"""Times scipy.spatial.Voronoi (Qhull) on points stored as raw x,y,z doubles.

usage: python3 scipy_voronoi.py <points.bin>; prints "seconds peak_mib regions".
Qhull gives the unbounded diagram's vertices and regions: no clipping, volumes or areas.
"""
import resource
import sys
import time

import numpy as np
from scipy.spatial import Voronoi

points = np.fromfile(sys.argv[1], dtype=np.float64).reshape(-1, 3)
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
diagram = Voronoi(points)
seconds = time.perf_counter() - start
peak = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base) / 1024.0
print(f"{seconds:.6f} {peak:.1f} {len(diagram.regions)}")
