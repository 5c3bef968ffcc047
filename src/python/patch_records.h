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

/// One record per JSON object (the layout of recordLayout, patch_table.h), one field per key
/// (sorted as nlohmann::json sorts them): a number is a float64 field (int64 when every record has
/// an integer there, bool for booleans), a rectangular list of numbers a float64/int64 subarray, an
/// object a nested structured field. A list whose length varies between records is padded with
/// zeros to the longest and gets a companion int64 field KEY_count with its length; "planes" (clip
/// planes of implicit patches) is always padded to QuadricPatch::kMaxPlanes rows of 4, a zero plane
/// keeping everything. A float the record lacks is NaN, anything else 0. Strings and nulls are left
/// out (nulls are NaN where the key is a number in another record). `empty` describes the records'
/// shape when there are none.
py::array recordsFromJson(const std::vector<nlohmann::json>& records,
                          const nlohmann::json& empty = nlohmann::json::object());

}  // namespace quadtri::python
