// Checks the pieces that the distributed filter wrote (TestMPI.py) against the one-process run:
// every input point is one rank's own point exactly once, ghost points repeat input points, the
// tetrahedra of all pieces (in input ids) are exactly those of vtkFastDelaunay3D on the whole
// input, each once, and pass the exact validator; every point keeps its point data ("Label", made
// from its coordinates); the volume Integrate Variables found is that of
// the convex hull, once; the own points' Density is the one-process run's. With an alpha, the alpha
// shape's cells of every dimension are compared. Weighted points (a "Radius" point array, which
// the filter weighed the points by): the regular tetrahedralization, its hidden points counted and
// truly hidden.
//
// usage: CheckDistributed <pieces .pvtu> <volume printed by TestMPI.py> [alpha]
#include "ExactValidator.h"
#include "VtkTestUtilities.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFastDelaunay3D.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLPUnstructuredGridReader.h"

#include "fd3/Measures.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <numeric>
#include <utility>

namespace
{
int fail(const std::string& why)
{
  std::cerr << "CheckDistributed: " << why << "\n";
  return 1;
}

/// Every cell as the sorted list of the first copies of its points (ids through `toInput`), all
/// cells sorted: equal for two grids exactly when they have the same cells.
std::vector<std::vector<std::uint32_t>> cellSet(vtkUnstructuredGrid* grid,
  const std::vector<std::uint32_t>& firstCopy, const std::vector<std::uint32_t>& toInput)
{
  std::vector<std::vector<std::uint32_t>> cells;
  vtkIdType size;
  const vtkIdType* ids;
  auto it = vtk::TakeSmartPointer(grid->GetCells()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    it->GetCurrentCell(size, ids);
    std::vector<std::uint32_t> cell(size);
    for (vtkIdType k = 0; k < size; ++k)
      cell[k] = firstCopy[toInput[ids[k]]];
    std::sort(cell.begin(), cell.end());
    cells.push_back(cell);
  }
  std::sort(cells.begin(), cells.end());
  return cells;
}

/// The input, rebuilt in input order from the points each rank owns, with `toInput` (output id to
/// input id) and, where the points have a "Radius" array, `radii`; an error when a point is owned
/// other than once, a ghost differs from its point, or a point has another's point data.
std::string rebuildInput(vtkUnstructuredGrid* pieces, fd3test::Points& input,
  std::vector<std::uint32_t>& toInput, std::vector<double>& radii)
{
  auto* inputIds = vtkIdTypeArray::SafeDownCast(pieces->GetPointData()->GetArray("GlobalIds"));
  auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
    pieces->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  if (!inputIds || !ghosts)
    return "no GlobalIds or vtkGhostType point array";
  const fd3test::Points xyz = fd3test::coordinates(pieces);
  const vtkIdType n = pieces->GetNumberOfPoints();
  vtkIdType inputCount = 0;
  for (vtkIdType i = 0; i < n; ++i)
    inputCount += ghosts->GetValue(i) == 0;
  input.assign(3 * inputCount, NAN);
  vtkDataArray* radius = pieces->GetPointData()->GetArray("Radius");
  radii.assign(radius ? inputCount : 0, NAN);
  std::vector<int> seen(inputCount, 0);
  toInput.resize(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const vtkIdType id = inputIds->GetValue(i);
    if (id < 0 || id >= inputCount)
      return "input id out of range";
    toInput[i] = static_cast<std::uint32_t>(id);
    if (ghosts->GetValue(i) == 0)
    {
      ++seen[id];
      std::copy_n(&xyz[3 * i], 3, &input[3 * id]);
      if (radius)
        radii[id] = radius->GetComponent(i, 0);
    }
  }
  for (vtkIdType id = 0; id < inputCount; ++id)
    if (seen[id] != 1)
      return "input point " + std::to_string(id) + " owned " + std::to_string(seen[id]) + " times";
  for (vtkIdType i = 0; i < n; ++i)
    if (!std::equal(&xyz[3 * i], &xyz[3 * i + 3], &input[3 * toInput[i]]))
      return "a ghost point differs from the input point it repeats";
  vtkDataArray* label = pieces->GetPointData()->GetArray("Label");
  if (!label)
    return "the input's point data is lost";
  for (vtkIdType i = 0; i < n; ++i)
    if (label->GetComponent(i, 0) != xyz[3 * i] / 4 + xyz[3 * i + 1] / 2 + xyz[3 * i + 2])
      return "point " + std::to_string(i) + " has another point's data";
  return "";
}

/// The figures of all ranks together, from the pieces' field data, against the one-process run's.
std::string compareFigures(vtkUnstructuredGrid* pieces, vtkFastDelaunay3D* serial)
{
  const std::pair<const char*, vtkIdType> counts[] = {
    {"NumberOfInsertedPoints", serial->GetNumberOfInsertedPoints()},
    {"NumberOfDuplicatePoints", serial->GetNumberOfDuplicatePoints()},
    {"NumberOfInvalidPoints", serial->GetNumberOfInvalidPoints()},
    {"NumberOfHiddenPoints", serial->GetNumberOfHiddenPoints()},
    {"NumberOfTetrahedra", serial->GetNumberOfTetrahedra()}};
  for (const auto& [name, expected] : counts)
  {
    vtkDataArray* figure = pieces->GetFieldData()->GetArray(name);
    if (!figure || figure->GetComponent(0, 0) != double(expected))
      return std::string(name) + " is " +
        (figure ? std::to_string(figure->GetComponent(0, 0)) : "missing") +
        ", the one-process run's " + std::to_string(expected);
  }
  return "";
}

/// Each rank's own points' Density, against the one-process run's (NaN where it has NaN): the
/// halo gives a rank every tetrahedron around its points.
std::string compareDensity(vtkUnstructuredGrid* pieces, vtkUnstructuredGrid* serial,
  const std::vector<std::uint32_t>& toInput)
{
  vtkDataArray* density = pieces->GetPointData()->GetArray("Density");
  vtkDataArray* expected = serial->GetPointData()->GetArray("Density");
  auto* ghosts = pieces->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName());
  if (!density || !expected)
    return "no Density point array";
  for (vtkIdType i = 0; i < pieces->GetNumberOfPoints(); ++i)
  {
    if (ghosts->GetComponent(i, 0) != 0)
      continue;
    const double d = density->GetComponent(i, 0), e = expected->GetComponent(toInput[i], 0);
    if (std::isnan(d) != std::isnan(e) || std::abs(d - e) > 1e-12 * std::abs(e))
      return "point " + std::to_string(toInput[i]) + " has density " + std::to_string(d) +
        ", the one-process run " + std::to_string(e);
  }
  return "";
}

/// The volume of the grid's tetrahedra (with an alpha, of its alpha shape's).
double volume(vtkUnstructuredGrid* grid, const fd3test::Points& xyz)
{
  double total = 0;
  vtkIdType size;
  const vtkIdType* ids;
  auto it = vtk::TakeSmartPointer(grid->GetCells()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    it->GetCurrentCell(size, ids);
    if (size == 4)
      total += std::abs(fd3::sixVolume(
                 &xyz[3 * ids[0]], &xyz[3 * ids[1]], &xyz[3 * ids[2]], &xyz[3 * ids[3]])) /
        6;
  }
  return total;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
    return fail("usage: CheckDistributed <pieces .pvtu> <volume> [alpha]");
  const double alpha = argc > 3 ? std::atof(argv[3]) : 0.0;
  vtkNew<vtkXMLPUnstructuredGridReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkUnstructuredGrid* pieces = reader->GetOutput();
  fd3test::Points input;
  std::vector<std::uint32_t> toInput;
  std::vector<double> radii;
  if (const std::string failure = rebuildInput(pieces, input, toInput, radii); !failure.empty())
    return fail(failure);
  const std::size_t inputCount = input.size() / 3;

  vtkNew<vtkFastDelaunay3D> serial;
  vtkSmartPointer<vtkPolyData> whole = fd3test::toPolyData(input);
  std::vector<double> weights;
  if (!radii.empty())
  {
    vtkNew<vtkDoubleArray> radius;
    radius->SetName("Radius");
    for (const double r : radii)
    {
      radius->InsertNextValue(r);
      weights.push_back(r * r);
    }
    whole->GetPointData()->AddArray(radius);
    serial->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
    serial->WeightsAreRadiiOn();
  }
  serial->SetInputData(whole);
  serial->SetAlpha(alpha);
  serial->ComputeDensityOn();
  serial->Update();
  std::vector<std::uint32_t> identity(inputCount);
  std::iota(identity.begin(), identity.end(), 0u);
  const std::vector<std::uint32_t> firstCopy = fd3test::firstCopies(input);
  const auto cells = cellSet(pieces, firstCopy, toInput);
  if (cells != cellSet(serial->GetOutput(), firstCopy, identity))
    return fail("the pieces' cells (" + std::to_string(cells.size()) +
      ") differ from the one-process run's (" +
      std::to_string(serial->GetOutput()->GetNumberOfCells()) + ")");
  if (const std::string failure = compareFigures(pieces, serial); !failure.empty())
    return fail(failure);
  if (const std::string failure = compareDensity(pieces, serial->GetOutput(), toInput);
      !failure.empty())
    return fail(failure);
  if (alpha == 0)
  {
    std::vector<std::uint32_t> tets = fd3test::tetrahedra(pieces);
    for (auto& id : tets)
      id = toInput[id];
    fd3test::ValidityOptions check;
    if (!weights.empty()) // hidden: the first copies of a position that no tetrahedron uses
    {
      check.weights = weights.data();
      std::vector<bool> used(inputCount, false);
      for (const std::uint32_t id : tets)
        used[firstCopy[id]] = true;
      for (std::uint32_t id = 0; id < inputCount; ++id)
        if (firstCopy[id] == id && !used[id])
          check.hidden.push_back(id);
      if (check.hidden.empty())
        return fail("no point is hidden: the weights are not used");
    }
    const fd3test::ValidityReport report =
      fd3test::checkTriangulation(input.data(), inputCount, tets, check);
    if (!report.valid())
      return fail(report.summary());
  }
  const double hull = volume(serial->GetOutput(), input);
  const double integrated = std::atof(argv[2]);
  if (!(std::abs(integrated - hull) <= 1e-9 * hull))
    return fail("Integrate Variables gives " + std::string(argv[2]) + ", the hull's volume is " +
      std::to_string(hull));
  std::cout << "CheckDistributed: OK, " << cells.size() << " cells of " << inputCount << " points, "
            << pieces->GetNumberOfPoints() - vtkIdType(inputCount) << " ghost points\n";
  return 0;
}
