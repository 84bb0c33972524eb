// Checks the Voronoi cells that the distributed filter wrote (TestMPI.py ... voronoi) against the
// one-process run on the same points: every generator has one cell on one rank, with the volume,
// surface area, faces and neighbours of its one-process cell; the cells keep their points' data
// ("Label", made from the coordinates); their Density is the one-process run's (but where ties
// let a rank pick other tetrahedra); the pieces' volumes fill the box; the ranks' faces outputs
// together have the one-process faces (count and area); the duplicates are counted across ranks.
// Weighted points (a "Radius" array, which the filter weighed the points by): power cells, a
// hidden point's empty, the hidden points counted across ranks as one process counts them.
//
// usage: CheckDistributedVoronoi <pieces .pvtu> <kind, as TestMPI.py's> <faces> <their area>
#include "VtkTestUtilities.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFastVoronoi3D.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLPUnstructuredGridReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>

namespace
{
int fail(const std::string& why)
{
  std::cerr << "CheckDistributedVoronoi: " << why << "\n";
  return 1;
}

std::string text(double x)
{
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

/// TestMPI.py repeats its first 50 points.
constexpr double kDuplicates = 50;

/// A cell's figures, by generator id.
struct Cell
{
  double volume, area, density;
  int faces, neighbors;
};

std::string cellsOf(vtkUnstructuredGrid* grid, std::map<vtkIdType, Cell>& cells)
{
  vtkCellData* data = grid->GetCellData();
  vtkDataArray* ids = data->GetArray("GeneratorId");
  vtkDataArray* volume = data->GetArray("Volume");
  vtkDataArray* area = data->GetArray("SurfaceArea");
  vtkDataArray* faces = data->GetArray("NumberOfFaces");
  vtkDataArray* neighbors = data->GetArray("NumberOfNeighbors");
  vtkDataArray* density = data->GetArray("Density");
  if (!ids || !volume || !area || !faces || !neighbors || !density)
    return "a cell array is missing";
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const auto id = static_cast<vtkIdType>(ids->GetComponent(c, 0));
    const Cell cell = {volume->GetComponent(c, 0), area->GetComponent(c, 0),
      density->GetComponent(c, 0), int(faces->GetComponent(c, 0)),
      int(neighbors->GetComponent(c, 0))};
    if (!cells.emplace(id, cell).second)
      return "generator " + std::to_string(id) + " has two cells";
  }
  return "";
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 5)
    return fail("usage: CheckDistributedVoronoi <pieces .pvtu> <kind> <faces> <their area>");
  const bool ties = std::string(argv[2]) == "lattice" || std::string(argv[2]) == "sphere";
  vtkNew<vtkXMLPUnstructuredGridReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkUnstructuredGrid* pieces = reader->GetOutput();
  std::map<vtkIdType, Cell> distributed;
  if (const std::string failure = cellsOf(pieces, distributed); !failure.empty())
    return fail(failure);
  vtkDataArray* position = pieces->GetCellData()->GetArray("Position");
  vtkDataArray* label = pieces->GetCellData()->GetArray("Label");
  vtkDataArray* generatorIds = pieces->GetCellData()->GetArray("GeneratorId");
  vtkDataArray* radius = pieces->GetCellData()->GetArray("Radius");
  if (!position || !label)
    return fail("the input's point data is not on the cells");

  // The generators, one per cell, in the order of their ids: the one-process run's input.
  std::map<vtkIdType, std::array<double, 4>> byId; // x, y, z and the radius
  for (vtkIdType c = 0; c < pieces->GetNumberOfCells(); ++c)
  {
    std::array<double, 4> x;
    position->GetTuple(c, x.data());
    if (label->GetComponent(c, 0) != x[0] / 4 + x[1] / 2 + x[2])
      return fail("cell " + std::to_string(c) + " has another point's data");
    x[3] = radius ? radius->GetComponent(c, 0) : 0;
    byId[static_cast<vtkIdType>(generatorIds->GetComponent(c, 0))] = x;
  }
  fd3test::Points input;
  std::vector<vtkIdType> inputId;
  vtkNew<vtkDoubleArray> radii;
  radii->SetName("Radius");
  for (const auto& [id, x] : byId)
  {
    input.insert(input.end(), x.begin(), x.begin() + 3);
    radii->InsertNextValue(x[3]);
    inputId.push_back(id);
  }
  vtkNew<vtkFastVoronoi3D> serial;
  vtkSmartPointer<vtkPolyData> whole = fd3test::toPolyData(input);
  if (radius)
  {
    whole->GetPointData()->AddArray(radii);
    serial->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
    serial->WeightsAreRadiiOn();
  }
  serial->SetInputData(whole);
  serial->ComputeDensityOn();
  serial->GenerateFacesOn();
  serial->Update();
  std::map<vtkIdType, Cell> expected, renumbered;
  if (const std::string failure = cellsOf(serial->GetOutput(), expected); !failure.empty())
    return fail(failure);
  for (const auto& [k, cell] : expected)
    renumbered[inputId[k]] = cell;
  if (renumbered.size() != distributed.size())
    return fail(std::to_string(distributed.size()) + " cells, the one-process run has " +
      std::to_string(renumbered.size()));

  const double* box = serial->GetOutput()->GetBounds();
  const double boxVolume = (box[1] - box[0]) * (box[3] - box[2]) * (box[5] - box[4]);
  const double cellVolume = boxVolume / double(distributed.size());
  const double cellArea = std::pow(cellVolume, 2.0 / 3.0);
  double total = 0, doubled = 0, hidden = 0;
  for (const auto& [id, cell] : distributed)
  {
    const Cell& one = renumbered.at(id);
    // A rank computes a vertex from the same points as one process, in another order at times.
    if (!(std::abs(cell.volume - one.volume) <= 1e-12 * std::max(one.volume, cellVolume)) ||
      !(std::abs(cell.area - one.area) <= 1e-12 * std::max(one.area, cellArea)))
      return fail("generator " + std::to_string(id) + ": volume " + text(cell.volume) + ", area " +
        text(cell.area) + "; one process: " + text(one.volume) + ", " + text(one.area));
    if (cell.faces != one.faces || cell.neighbors != one.neighbors)
      return fail("generator " + std::to_string(id) + ": " + std::to_string(cell.faces) +
        " faces, " + std::to_string(cell.neighbors) + " neighbours; one process: " +
        std::to_string(one.faces) + ", " + std::to_string(one.neighbors));
    // The one-process run here has no duplicates: a generator that had one has twice the mass.
    // On a lattice a rank breaks ties in its own frame, and may pick other tetrahedra.
    // A speck's cells have no volume in doubles: their density is infinite in both.
    const bool same = cell.density == one.density || // NaN: a hidden generator's
      (std::isnan(cell.density) && std::isnan(one.density));
    const double ratio = same ? 1 : cell.density / one.density;
    if (!ties && !(std::abs(ratio - 1) < 1e-9 || std::abs(ratio - 2) < 1e-9))
      return fail("generator " + std::to_string(id) + ": density " + text(cell.density) +
        ", one process " + text(one.density));
    doubled += std::abs(ratio - 2) < 1e-9;
    hidden += std::isnan(one.density);
    total += cell.volume;
  }
  // A hidden point has no density (NaN) to double, whether it has a duplicate or not.
  if (!ties && !(doubled <= kDuplicates && doubled + hidden >= kDuplicates))
    return fail(std::to_string(doubled) + " cells have a duplicate's mass in their density");
  if (!(std::abs(total - boxVolume) <= 1e-9 * boxVolume))
    return fail("the cells' volumes add up to " + std::to_string(total) + ", the box's is " +
      std::to_string(boxVolume));
  // The faces output of all ranks: each face once, as one process has them.
  vtkPolyData* faces = serial->GetFacesOutput();
  vtkDataArray* areas = faces->GetCellData()->GetArray("Area");
  double area = 0;
  for (vtkIdType f = 0; f < faces->GetNumberOfCells(); ++f)
    area += areas->GetTuple1(f);
  if (std::atoll(argv[3]) != faces->GetNumberOfCells() ||
    !(std::abs(std::atof(argv[4]) - area) <= 1e-9 * area))
    return fail(std::string("the ranks' faces: ") + argv[3] + " of area " + argv[4] +
      "; one process: " + std::to_string(faces->GetNumberOfCells()) + " of area " + text(area));
  vtkDataArray* duplicates = pieces->GetFieldData()->GetArray("NumberOfDuplicatePoints");
  if (!duplicates || duplicates->GetComponent(0, 0) != kDuplicates)
    return fail("the duplicates are not counted across ranks");
  if (radius)
  {
    vtkDataArray* hidden = pieces->GetFieldData()->GetArray("NumberOfHiddenPoints");
    if (serial->GetNumberOfHiddenPoints() == 0 || !hidden ||
      hidden->GetComponent(0, 0) != double(serial->GetNumberOfHiddenPoints()))
      return fail("the hidden points are not counted across ranks as one process counts them (" +
        std::to_string(serial->GetNumberOfHiddenPoints()) + ")");
  }
  std::cout << "CheckDistributedVoronoi: OK, " << distributed.size() << " cells\n";
  return 0;
}
