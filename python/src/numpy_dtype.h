#pragma once

// numpy structured dtypes for arrays whose rows are C++ records (LiDAR points, trajectory rows),
// so that one memcpy-able struct is one array row, without a Python object per row.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <initializer_list>

namespace corsa::python {

/// One named field of a record: its numpy format ("<f8", "<u4", "?") and its byte offset.
struct DtypeField {
  const char* name;
  const char* format;
  size_t offset;
};

/// The dtype of a record `itemsize` bytes long with `fields` at their offsets (padding between
/// them is kept, so the array's memory is the records' memory).
inline pybind11::dtype record_dtype(std::initializer_list<DtypeField> fields, size_t itemsize) {
  pybind11::list names, formats, offsets;
  for (const DtypeField& field : fields) {
    names.append(field.name);
    formats.append(field.format);
    offsets.append(field.offset);
  }
  pybind11::dict spec;
  spec["names"] = names;
  spec["formats"] = formats;
  spec["offsets"] = offsets;
  spec["itemsize"] = itemsize;
  return pybind11::dtype::from_args(spec);
}

}  // namespace corsa::python
