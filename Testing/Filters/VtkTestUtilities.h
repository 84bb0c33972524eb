// Conversions between the test point sets and VTK data, shared by the VTK tests and the benchmark.
#ifndef fd3_VtkTestUtilities_h
#define fd3_VtkTestUtilities_h

#include "ExactValidator.h"
#include "PointSets.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstdint>
#include <vector>

class vtkDataArray;
class vtkPointSet;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace fd3test
{

/// The points as a vtkPolyData without cells, coordinates of the given VTK type.
vtkSmartPointer<vtkPolyData> toPolyData(const Points& p, int type = VTK_DOUBLE);

/// The connectivity of the grid's cells, 4 ids each, in the grid's order (which keeps the
/// orientation). Empty when any cell is not a tetrahedron, so that a validity check then fails.
std::vector<std::uint32_t> tetrahedra(vtkUnstructuredGrid* grid);

/// The points' coordinates as doubles, whatever their VTK type.
Points coordinates(vtkPointSet* data);

/// The sum of an array's first components (a cell array of volumes, say).
double sum(vtkDataArray* array);

/// The exact validator's report on a filter output: its tetrahedra over its own points.
ValidityReport checkOutput(
  vtkUnstructuredGrid* grid, const ValidityOptions& options = ValidityOptions());

} // namespace fd3test

#endif
