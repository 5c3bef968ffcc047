#include "patch_records.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

#include "quadtri/math/error.h"
#include "quadtri/surface/patch_table.h"

namespace quadtri::python {

namespace {

template <typename Json>
py::object toPythonImpl(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null:
      return py::none();
    case Json::value_t::boolean:
      return py::bool_(value.template get<bool>());
    case Json::value_t::number_integer:
      return py::int_(value.template get<int64_t>());
    case Json::value_t::number_unsigned:
      return py::int_(value.template get<uint64_t>());
    case Json::value_t::number_float:
      return py::float_(value.template get<double>());
    case Json::value_t::string:
      return py::str(value.template get<std::string>());
    case Json::value_t::array: {
      py::list list;
      for (const auto& item : value) list.append(toPythonImpl(item));
      return list;
    }
    case Json::value_t::object: {
      py::dict dict;
      for (const auto& [key, item] : value.items()) dict[py::str(key)] = toPythonImpl(item);
      return dict;
    }
    default:
      return py::none();
  }
}

}  // namespace

py::object dtypeOf(const RecordField& node) {
  py::list fields;
  for (const RecordField& child : node.children) {
    const std::string& key = child.name;
    if (child.kind == RecordField::Kind::Object) {
      fields.append(py::make_tuple(key, dtypeOf(child)));
      continue;
    }
    const char* type = child.kind == RecordField::Kind::Bool  ? "?"
                       : child.kind == RecordField::Kind::Int ? "<i8"
                                                              : "<f8";
    if (child.dims.empty()) {
      fields.append(py::make_tuple(key, type));
    } else {
      py::tuple shape(child.dims.size());
      for (size_t d = 0; d < child.dims.size(); ++d) shape[d] = py::int_(child.dims[d]);
      fields.append(py::make_tuple(key, type, shape));
    }
    if (child.variable) fields.append(py::make_tuple(key + "_count", "<i8"));
  }
  return py::module_::import("numpy").attr("dtype")(fields);
}

py::object toPython(const nlohmann::json& value) {
  return toPythonImpl(value);
}

py::object toPython(const nlohmann::ordered_json& value) {
  return toPythonImpl(value);
}

py::array recordsFromBytes(const RecordLayout& layout, const char* bytes, size_t count) {
  const py::dtype dtype = py::reinterpret_borrow<py::dtype>(dtypeOf(layout.root()));
  if (size_t(dtype.itemsize()) != layout.itemSize())
    fail("internal: record layout of {} bytes, numpy's dtype has {}", layout.itemSize(),
         dtype.itemsize());
  py::array out(dtype, std::vector<py::ssize_t>{py::ssize_t(count)});
  if (count > 0) std::memcpy(out.mutable_data(), bytes, count * layout.itemSize());
  return out;
}

}  // namespace quadtri::python
