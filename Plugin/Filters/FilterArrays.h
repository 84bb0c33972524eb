/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// The small array helpers that the filters of FastDelaunay3D::Filters share (a private header of
// the module).
#ifndef FilterArrays_h
#define FilterArrays_h

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

namespace fd3vtk
{
/// A new array named `name` with `tuples` tuples (one component).
template <typename ArrayType>
vtkSmartPointer<ArrayType> NamedArray(const char* name, vtkIdType tuples)
{
  auto array = vtkSmartPointer<ArrayType>::New();
  array->SetName(name);
  array->SetNumberOfTuples(tuples);
  return array;
}

/// A one-tuple double array `name` holding `value`, added to `fields`.
inline void AddFieldValue(vtkFieldData* fields, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  fields->AddArray(array);
}
} // namespace fd3vtk

#endif
