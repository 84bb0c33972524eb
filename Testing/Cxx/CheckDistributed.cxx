// Checks the pieces that the distributed filter wrote (TestMPI.py) against the one-process run:
// every input point is one rank's own point exactly once, ghost points repeat input points, the
// tetrahedra of all pieces (in input ids) are exactly those of vtkFastDelaunay3D on the whole
// input, each once, and pass the exact validator; the volume Integrate Variables found is that of
// the convex hull, once.
//
// usage: CheckDistributed <pieces .pvtu> <volume printed by TestMPI.py>
#include "ExactValidator.h"
#include "VtkTestUtilities.h"

#include "vtkDataSetAttributes.h"
#include "vtkFastDelaunay3D.h"
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
#include <map>

namespace
{
int fail(const std::string& why)
{
  std::cerr << "CheckDistributed: " << why << "\n";
  return 1;
}

/// Every id replaced by the first id of its position, so that duplicates compare equal.
std::vector<std::uint32_t> byFirstCopy(const fd3test::Points& p, std::vector<std::uint32_t> ids)
{
  std::map<std::array<double, 3>, std::uint32_t> first;
  std::vector<std::uint32_t> copy(p.size() / 3);
  for (std::uint32_t i = 0; i < copy.size(); ++i)
    copy[i] = first.emplace(std::array<double, 3>{p[3 * i], p[3 * i + 1], p[3 * i + 2]}, i).first->second;
  for (auto& id : ids)
    id = copy[id];
  return ids;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
    return fail("usage: CheckDistributed <pieces .pvtu> <volume>");
  vtkNew<vtkXMLPUnstructuredGridReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkUnstructuredGrid* pieces = reader->GetOutput();
  auto* inputIds = vtkIdTypeArray::SafeDownCast(pieces->GetPointData()->GetArray("GlobalIds"));
  auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
    pieces->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  if (!inputIds || !ghosts)
    return fail("no GlobalIds or vtkGhostType point array");
  const fd3test::Points xyz = fd3test::coordinates(pieces);
  const vtkIdType n = pieces->GetNumberOfPoints();

  // The input, rebuilt in input order from the points each rank owns.
  vtkIdType inputCount = 0;
  for (vtkIdType i = 0; i < n; ++i)
    inputCount += ghosts->GetValue(i) == 0;
  fd3test::Points input(3 * inputCount, NAN);
  std::vector<int> seen(inputCount, 0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const vtkIdType id = inputIds->GetValue(i);
    if (id < 0 || id >= inputCount)
      return fail("input id out of range");
    if (ghosts->GetValue(i) == 0)
    {
      ++seen[id];
      std::copy_n(&xyz[3 * i], 3, &input[3 * id]);
    }
  }
  for (vtkIdType id = 0; id < inputCount; ++id)
    if (seen[id] != 1)
      return fail("input point " + std::to_string(id) + " owned " + std::to_string(seen[id]) + " times");
  for (vtkIdType i = 0; i < n; ++i)
    if (!std::equal(&xyz[3 * i], &xyz[3 * i + 3], &input[3 * inputIds->GetValue(i)]))
      return fail("a ghost point differs from the input point it repeats");

  std::vector<std::uint32_t> tets = fd3test::tetrahedra(pieces);
  if (tets.size() != 4 * static_cast<std::size_t>(pieces->GetNumberOfCells()))
    return fail("a cell is not a tetrahedron");
  for (auto& id : tets)
    id = static_cast<std::uint32_t>(inputIds->GetValue(id));

  vtkNew<vtkFastDelaunay3D> serial;
  serial->SetInputData(fd3test::toPolyData(input));
  serial->Update();
  const std::vector<std::uint32_t> reference = fd3test::tetrahedra(serial->GetOutput());
  if (fd3test::canonicalTetrahedra(byFirstCopy(input, tets)) !=
    fd3test::canonicalTetrahedra(byFirstCopy(input, reference)))
    return fail("the pieces' tetrahedra (" + std::to_string(tets.size() / 4) +
      ") differ from the one-process run's (" + std::to_string(reference.size() / 4) + ")");
  const fd3test::ValidityReport report = fd3test::checkTriangulation(input.data(), inputCount, tets);
  if (!report.valid())
    return fail(report.summary());

  double hull = 0;
  for (std::size_t t = 0; t < reference.size(); t += 4)
    hull += fd3::sixVolume(&input[3 * reference[t]], &input[3 * reference[t + 1]],
              &input[3 * reference[t + 2]], &input[3 * reference[t + 3]]) / 6;
  const double integrated = std::atof(argv[2]);
  if (!(std::abs(integrated - hull) <= 1e-9 * hull))
    return fail("Integrate Variables gives " + std::string(argv[2]) + ", the hull's volume is " +
      std::to_string(hull));
  std::cout << "CheckDistributed: OK, " << tets.size() / 4 << " tetrahedra of " << inputCount
            << " points, " << n - inputCount << " ghost points\n";
  return 0;
}
