// The typed properties and nested objects of one plugin element (<sensor>, <bsdf>, ...). A
// plugin reads what it knows through typed getters; whatever it did not read is an error, so
// that misspelt or unsupported parameters never pass silently.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"
#include "xml_file.h"

namespace quadtri {

/// The largest sample count a scene may ask for (a sampler's sample_count, an integrator's
/// per-pixel or per-vertex samples): 2^24, where a float still counts samples exactly.
constexpr int kMaxSceneSamples = 1 << 24;

/// The XML tag a property was written with.
enum class PropertyType {
  Float,
  Integer,
  Boolean,
  String,
  Rgb,
  Point,
  Vector,
  Transform,
  Spectrum
};

/// One <float>/<integer>/.../<transform> child, parsed.
struct Property {
  std::string name;
  PropertyType type;
  std::variant<double, long long, bool, std::string, Color, Vec3, Mat4> value;
  XmlElement element;
  bool used = false;
};

/// The properties and nested objects of a plugin element, queried by name and type.
class ObjectProperties {
 public:
  /// Reads the element's children; `allowedNested` are the object tags it may contain
  /// (e.g. "film", "sampler"). Checks the element's own attributes (type, id, name).
  ObjectProperties(const XmlElement& element, std::vector<std::string_view> allowedNested);

  const XmlElement& element() const { return element_; }
  const std::string& type() const { return type_; }
  const std::string& id() const { return id_; }
  std::string location() const { return element_.location(); }

  /// <float> or <integer>; `fallback` when absent, or an error when there is none.
  double getFloat(std::string_view name, std::optional<double> fallback = std::nullopt);
  long long getInteger(std::string_view name, std::optional<long long> fallback = std::nullopt);
  /// <integer>, or nullopt when absent.
  std::optional<long long> getOptionalInteger(std::string_view name);
  bool getBoolean(std::string_view name, std::optional<bool> fallback = std::nullopt);
  std::string getString(std::string_view name, std::optional<std::string> fallback = std::nullopt);
  /// <rgb>, <spectrum> (one value, or wavelength:value pairs converted to RGB; spectrum.h)
  /// or a <float> grey level.
  Color getColor(std::string_view name, std::optional<Color> fallback = std::nullopt);
  /// <point> or <vector>.
  Vec3 getVector(std::string_view name, std::optional<Vec3> fallback = std::nullopt);
  /// <transform>; nullopt when absent.
  std::optional<Mat4> getTransform(std::string_view name);
  /// A <float> or a <string> (index of refraction given by value or by medium name).
  std::variant<double, std::string> getFloatOrString(std::string_view name,
                                                     std::variant<double, std::string> fallback);

  bool has(std::string_view name) const { return find(name) != nullptr; }
  /// Accepts `name` (of any type) without using it: when present, appends "FILE:LINE: note:
  /// <object>: <name> ignored (<why>)" to `notes`. For Mitsuba properties that do not change
  /// quadtri's image.
  void ignore(std::string_view name, std::string_view why, std::vector<std::string>& notes);
  /// The element of a property, for errors about its value (the object's own when absent).
  const XmlElement& at(std::string_view name) const;
  /// Throws "FILE:LINE: <what>" at the property (or object) named `name`.
  template <typename... Args>
  [[noreturn]] void fail(std::string_view name, fmt::format_string<Args...> format,
                         Args&&... args) const {
    at(name).fail("{}: {} {}", describe(), name, fmt::format(format, std::forward<Args>(args)...));
  }

  /// Removes and returns the nested objects with this tag, in document order.
  std::vector<XmlElement> takeNested(std::string_view tag);
  /// Removes and returns the nested objects with any of these tags, in document order.
  std::vector<XmlElement> takeNested(std::initializer_list<std::string_view> tags);
  /// The nested object with this tag, if any; throws when there are several.
  std::optional<XmlElement> takeOptional(std::string_view tag);
  /// Throws for any property the plugin did not read or nested object it did not take, listing
  /// what the plugin reads.
  void finish() const;
  /// "sensor 'perspective'", for messages.
  std::string describe() const;

 private:
  const Property* find(std::string_view name) const;
  Property* use(std::string_view name);
  [[noreturn]] void wrongType(const Property& p, std::string_view expected) const;

  XmlElement element_;
  std::string type_;
  std::string id_;
  std::vector<Property> properties_;
  std::vector<XmlElement> nested_;
  std::vector<std::string> queried_;
};

}  // namespace quadtri
