#include "properties.h"

#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>

#include "quadtri/scene/spectrum.h"
#include "transform_xml.h"

namespace quadtri {

namespace {

constexpr std::string_view kPropertyTags[] = {"float", "integer", "boolean",   "string",  "rgb",
                                              "point", "vector",  "transform", "spectrum"};

/// <spectrum value="0.5"/> or <spectrum value="400:0.1, 500:0.5, 600:0.3"/>.
Color parseSpectrum(const XmlElement& e, std::string_view name) {
  if (e.has("filename"))
    e.fail(
        "{}: <spectrum filename=...> (a spectral data file) is not supported; give the "
        "values inline as wavelength:value pairs",
        name);
  const std::string_view text = e.required("value");
  if (text.find(':') == std::string_view::npos) {
    const std::vector<double> v = parseNumberList(e, text, name);
    if (v.size() != 1)
      e.fail("{}: <spectrum> value must be one number or wavelength:value pairs, got {} numbers",
             name, v.size());
    return Color::Constant(v[0]);
  }
  std::vector<double> nm, values;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view pair = text.substr(start, end - start);
    while (!pair.empty() && std::isspace(static_cast<unsigned char>(pair.front())))
      pair.remove_prefix(1);
    while (!pair.empty() && std::isspace(static_cast<unsigned char>(pair.back())))
      pair.remove_suffix(1);
    const size_t colon = pair.find(':');
    if (colon == std::string_view::npos)
      e.fail("{}: spectrum entry '{}' is not wavelength:value", name, pair);
    nm.push_back(parseNumber(e, pair.substr(0, colon), name));
    values.push_back(parseNumber(e, pair.substr(colon + 1), name));
    start = end + 1;
  }
  try {
    return spectrumToRgb(nm, values);
  } catch (const Error& error) {
    e.fail("{}: {}", name, error.what());
  }
}

std::string_view typeName(PropertyType type) {
  return kPropertyTags[int(type)];
}

/// Parses one property element into its typed value.
Property parseProperty(const XmlElement& e, PropertyType type) {
  Property p{std::string(e.required("name")), type, 0.0, e};
  switch (type) {
    case PropertyType::Float:
      e.checkAttributes({"name", "value"});
      p.value = parseNumber(e, e.required("value"), p.name);
      break;
    case PropertyType::Integer:
      e.checkAttributes({"name", "value"});
      p.value = parseInteger(e, e.required("value"), p.name);
      break;
    case PropertyType::Boolean: {
      e.checkAttributes({"name", "value"});
      std::string v(e.required("value"));
      std::transform(v.begin(), v.end(), v.begin(),
                     [](unsigned char c) { return std::tolower(c); });
      if (v != "true" && v != "false")
        e.fail("{}: '{}' is not a boolean; expected true or false", p.name, e.attr("value"));
      p.value = v == "true";
      break;
    }
    case PropertyType::String:
      e.checkAttributes({"name", "value"});
      p.value = std::string(e.attr("value"));
      break;
    case PropertyType::Rgb: {
      e.checkAttributes({"name", "value"});
      const std::vector<double> v = parseNumberList(e, e.required("value"), p.name);
      if (v.size() == 1) {
        p.value = Color(Color::Constant(v[0]));
      } else if (v.size() == 3) {
        p.value = Color(v[0], v[1], v[2]);
      } else {
        e.fail("{}: <rgb> value must have 1 or 3 numbers, got {}", p.name, v.size());
      }
      break;
    }
    case PropertyType::Point:
    case PropertyType::Vector:
      e.checkAttributes({"name", "value", "x", "y", "z"});
      p.value = parseXyz(e, 0.0);
      break;
    case PropertyType::Transform:
      e.checkAttributes({"name"});
      p.value = parseTransform(e);
      break;
    case PropertyType::Spectrum:
      e.checkAttributes({"name", "value", "filename"});
      p.value = parseSpectrum(e, p.name);
      break;
  }
  return p;
}

}  // namespace

ObjectProperties::ObjectProperties(const XmlElement& element,
                                   std::vector<std::string_view> allowedNested)
    : element_(element) {
  element.checkAttributes({"type", "id", "name"});
  type_ = std::string(element.required("type"));
  id_ = std::string(element.attr("id"));
  for (const XmlElement& child : element.children()) {
    const std::string_view tag = child.tag();
    const auto* known = std::find(std::begin(kPropertyTags), std::end(kPropertyTags), tag);
    if (known != std::end(kPropertyTags)) {
      Property p = parseProperty(child, PropertyType(known - std::begin(kPropertyTags)));
      if (const Property* previous = find(p.name))
        child.fail("{} sets '{}' twice (first at {})", describe(), p.name,
                   previous->element.location());
      properties_.push_back(std::move(p));
    } else if (std::find(allowedNested.begin(), allowedNested.end(), tag) != allowedNested.end()) {
      nested_.push_back(child);
    } else if (allowedNested.empty()) {
      child.fail("unknown element <{}> inside {}; expected a property ({})", tag, describe(),
                 fmt::join(kPropertyTags, ", "));
    } else {
      child.fail("unknown element <{}> inside {}; expected a property or one of {}", tag,
                 describe(), fmt::join(allowedNested, ", "));
    }
  }
}

std::string ObjectProperties::describe() const {
  return fmt::format("{} '{}'", element_.tag(), type_);
}

const Property* ObjectProperties::find(std::string_view name) const {
  for (const Property& p : properties_)
    if (p.name == name) return &p;
  return nullptr;
}

Property* ObjectProperties::use(std::string_view name) {
  if (std::find(queried_.begin(), queried_.end(), name) == queried_.end())
    queried_.emplace_back(name);
  for (Property& p : properties_)
    if (p.name == name) {
      p.used = true;
      return &p;
    }
  return nullptr;
}

const XmlElement& ObjectProperties::at(std::string_view name) const {
  const Property* p = find(name);
  return p ? p->element : element_;
}

void ObjectProperties::wrongType(const Property& p, std::string_view expected) const {
  p.element.fail("{}: property '{}' is <{}>, expected {}", describe(), p.name, typeName(p.type),
                 expected);
}

double ObjectProperties::getFloat(std::string_view name, std::optional<double> fallback) {
  const Property* p = use(name);
  if (!p) {
    if (!fallback) element_.fail("{} needs <float name=\"{}\" .../>", describe(), name);
    return *fallback;
  }
  if (p->type == PropertyType::Float) return std::get<double>(p->value);
  if (p->type == PropertyType::Integer) return double(std::get<long long>(p->value));
  wrongType(*p, "<float>");
}

long long ObjectProperties::getInteger(std::string_view name, std::optional<long long> fallback) {
  const Property* p = use(name);
  if (!p) {
    if (!fallback) element_.fail("{} needs <integer name=\"{}\" .../>", describe(), name);
    return *fallback;
  }
  if (p->type != PropertyType::Integer) wrongType(*p, "<integer>");
  return std::get<long long>(p->value);
}

std::optional<long long> ObjectProperties::getOptionalInteger(std::string_view name) {
  if (!has(name)) {
    use(name);
    return std::nullopt;
  }
  return getInteger(name);
}

bool ObjectProperties::getBoolean(std::string_view name, std::optional<bool> fallback) {
  const Property* p = use(name);
  if (!p) {
    if (!fallback) element_.fail("{} needs <boolean name=\"{}\" .../>", describe(), name);
    return *fallback;
  }
  if (p->type != PropertyType::Boolean) wrongType(*p, "<boolean>");
  return std::get<bool>(p->value);
}

std::string ObjectProperties::getString(std::string_view name,
                                        std::optional<std::string> fallback) {
  const Property* p = use(name);
  if (!p) {
    if (!fallback) element_.fail("{} needs <string name=\"{}\" .../>", describe(), name);
    return *fallback;
  }
  if (p->type != PropertyType::String) wrongType(*p, "<string>");
  return std::get<std::string>(p->value);
}

Color ObjectProperties::getColor(std::string_view name, std::optional<Color> fallback) {
  const Property* p = use(name);
  if (!p) {
    if (!fallback) element_.fail("{} needs <rgb name=\"{}\" .../>", describe(), name);
    return *fallback;
  }
  if (p->type == PropertyType::Rgb || p->type == PropertyType::Spectrum)
    return std::get<Color>(p->value);
  if (p->type == PropertyType::Float) return Color::Constant(std::get<double>(p->value));
  wrongType(*p, "<rgb>, <spectrum> or <float>");
}

Vec3 ObjectProperties::getVector(std::string_view name, std::optional<Vec3> fallback) {
  const Property* p = use(name);
  if (!p) {
    if (!fallback) element_.fail("{} needs <point name=\"{}\" .../>", describe(), name);
    return *fallback;
  }
  if (p->type != PropertyType::Point && p->type != PropertyType::Vector)
    wrongType(*p, "<point> or <vector>");
  return std::get<Vec3>(p->value);
}

std::optional<Mat4> ObjectProperties::getTransform(std::string_view name) {
  const Property* p = use(name);
  if (!p) return std::nullopt;
  if (p->type != PropertyType::Transform) wrongType(*p, "<transform>");
  return std::get<Mat4>(p->value);
}

std::variant<double, std::string> ObjectProperties::getFloatOrString(
    std::string_view name, std::variant<double, std::string> fallback) {
  const Property* p = use(name);
  if (!p) return fallback;
  if (p->type == PropertyType::Float) return std::get<double>(p->value);
  if (p->type == PropertyType::Integer) return double(std::get<long long>(p->value));
  if (p->type == PropertyType::String) return std::get<std::string>(p->value);
  wrongType(*p, "<float> or <string>");
}

std::vector<XmlElement> ObjectProperties::takeNested(std::string_view tag) {
  std::vector<XmlElement> out;
  for (auto it = nested_.begin(); it != nested_.end();) {
    if (it->tag() == tag) {
      out.push_back(*it);
      it = nested_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

std::vector<XmlElement> ObjectProperties::takeNested(std::initializer_list<std::string_view> tags) {
  std::vector<XmlElement> out;
  for (auto it = nested_.begin(); it != nested_.end();) {
    if (std::find(tags.begin(), tags.end(), it->tag()) != tags.end()) {
      out.push_back(*it);
      it = nested_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

std::optional<XmlElement> ObjectProperties::takeOptional(std::string_view tag) {
  std::vector<XmlElement> found = takeNested(tag);
  if (found.size() > 1) found[1].fail("{} has more than one <{}>", describe(), tag);
  if (found.empty()) return std::nullopt;
  return found.front();
}

void ObjectProperties::ignore(std::string_view name, std::string_view why,
                              std::vector<std::string>& notes) {
  const Property* p = use(name);
  if (p)
    notes.push_back(
        fmt::format("{}: note: {}: {} ignored ({})", p->element.location(), describe(), name, why));
}

void ObjectProperties::finish() const {
  for (const Property& p : properties_) {
    if (p.used) continue;
    if (queried_.empty()) p.element.fail("{} takes no properties, got '{}'", describe(), p.name);
    p.element.fail("unknown property '{}' for {}; expected one of {}", p.name, describe(),
                   fmt::join(queried_, ", "));
  }
  if (!nested_.empty())
    nested_.front().fail("<{}> is not allowed inside {}", nested_.front().tag(), describe());
}

}  // namespace quadtri
