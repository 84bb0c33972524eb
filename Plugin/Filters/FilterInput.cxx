/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "FilterInput.h"

#include "vtkAlgorithm.h"
#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

namespace
{
/// Copies x,y,z tuples of any real array into doubles, without a virtual call per tuple.
struct CopyToDoubles
{
  template <typename ArrayType>
  void operator()(ArrayType* array, double* out) const
  {
    const auto tuples = vtk::DataArrayTupleRange<3>(array);
    vtkSMPTools::For(0, tuples.size(), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType i = begin; i < end; ++i)
      {
        for (int k = 0; k < 3; ++k)
        {
          out[3 * i + k] = static_cast<double>(tuples[i][k]);
        }
      }
    });
  }
};
template <typename Algorithm>
auto CheckAbort(Algorithm* filter, int) -> decltype(filter->CheckAbort())
{
  return filter->CheckAbort();
}
template <typename Algorithm>
bool CheckAbort(Algorithm* filter, long)
{
  return filter->GetAbortExecute() != 0;
}
} // namespace

namespace fd3vtk
{
bool WeightsChosen(vtkAlgorithm* filter)
{
  vtkInformation* chosen = filter->GetInputArrayInformation(0);
  return chosen->Has(vtkDataObject::FIELD_NAME()) ||
    chosen->Has(vtkDataObject::FIELD_ATTRIBUTE_TYPE());
}

std::vector<double> PointWeights(
  vtkDataArray* array, vtkIdType inputPoints, bool radii, std::size_t count, std::string& problem)
{
  if (array->GetNumberOfComponents() != 1 || array->GetNumberOfTuples() != inputPoints)
  {
    problem = std::string("the weights array \"") + (array->GetName() ? array->GetName() : "") +
      "\" is not a point-data array of one component";
    return {};
  }
  std::vector<double> weights(count, 0.0);
  vtkSMPTools::For(0, inputPoints, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      const double value = array->GetComponent(i, 0);
      weights[static_cast<std::size_t>(i)] = radii ? value * value : value;
    }
  });
  return weights;
}

bool AbortRequested(vtkAlgorithm* filter)
{
  return CheckAbort(filter, 0);
}

vtkSmartPointer<vtkPoints> PointsInPrecision(vtkDataSet* input, int precision, vtkIdType extra)
{
  auto* pointSet = vtkPointSet::SafeDownCast(input);
  vtkPoints* given = pointSet ? pointSet->GetPoints() : nullptr;
  // As vtkDelaunay3D: DOUBLE_PRECISION doubles, DEFAULT_PRECISION the input's type, and any
  // other value floats.
  int type = VTK_FLOAT;
  if (precision == vtkAlgorithm::DEFAULT_PRECISION)
  {
    type = given ? given->GetDataType() : VTK_DOUBLE;
  }
  else if (precision == vtkAlgorithm::DOUBLE_PRECISION)
  {
    type = VTK_DOUBLE;
  }
  if (given && type == given->GetDataType() && extra == 0)
  {
    return given;
  }
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(type);
  points->SetNumberOfPoints(n + extra);
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    double x[3];
    for (vtkIdType i = begin; i < end; ++i)
    {
      input->GetPoint(i, x);
      points->SetPoint(i, x);
    }
  });
  return points;
}

const double* CoordinatesAsDoubles(vtkPoints* points, std::vector<double>& copy)
{
  vtkDataArray* data = points->GetData();
  if (auto* doubles = vtkDoubleArray::FastDownCast(data))
  {
    return doubles->GetPointer(0);
  }
  copy.resize(3 * static_cast<std::size_t>(points->GetNumberOfPoints()));
  using Reals = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
  if (!Reals::Execute(data, CopyToDoubles{}, copy.data()))
  {
    CopyToDoubles{}(data, copy.data());
  }
  return copy.data();
}

int ThreadCount(int numberOfThreads)
{
  return numberOfThreads > 0 ? numberOfThreads : vtkSMPTools::GetEstimatedNumberOfThreads();
}
} // namespace fd3vtk
