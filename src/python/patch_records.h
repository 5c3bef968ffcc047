// JSON values as Python objects, and lists of JSON records (a model's patch JSON) as numpy
// structured arrays.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "quadtri/surface/patch_table.h"

namespace quadtri::python {

namespace py = pybind11;

/// null → None, booleans, numbers, strings, arrays → list, objects → dict (in their order).
py::object toPython(const nlohmann::json& value);
py::object toPython(const nlohmann::ordered_json& value);

/// The numpy dtype of a record layout (patch_table.h): a field list, packed.
py::object dtypeOf(const RecordField& node);

/// `count` records of `layout` from `bytes` (count × layout.itemSize()), copied.
py::array recordsFromBytes(const RecordLayout& layout, const char* bytes, size_t count);

}  // namespace quadtri::python
