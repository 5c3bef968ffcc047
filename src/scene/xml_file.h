// One XML file of a scene and the element-level helpers every scene parser uses: locations
// ("FILE:LINE"), attribute checks, number lists and $name substitution.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <map>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "quadtri/math/error.h"

namespace quadtri {

/// A parsed XML document together with the line starts of its text, so that every node can be
/// named as "FILE:LINE".
/// Elements nest at most this deep (a scene needs about 6); deeper is refused as the file is read.
inline constexpr int kMaxXmlDepth = 64;

class XmlFile {
 public:
  /// Parses `text`; a syntax error throws Error "FILE:LINE: <pugixml's description>".
  XmlFile(std::string_view text, std::filesystem::path path);
  XmlFile(const XmlFile&) = delete;
  XmlFile& operator=(const XmlFile&) = delete;

  const std::filesystem::path& path() const { return path_; }
  pugi::xml_node root() const { return doc_.document_element(); }
  /// 1-based line of a byte offset into the text.
  size_t lineOf(ptrdiff_t offset) const;

 private:
  std::filesystem::path path_;
  std::vector<size_t> lineStarts_;
  pugi::xml_document doc_;
};

/// An element and the file it belongs to (scenes may <include> other files).
struct XmlElement {
  const XmlFile* file = nullptr;
  pugi::xml_node node;

  std::string_view tag() const { return node.name(); }
  /// "FILE:LINE" of the element's start tag.
  std::string location() const;
  /// The attribute's value, or "" when it is absent.
  std::string_view attr(const char* name) const { return node.attribute(name).value(); }
  bool has(const char* name) const { return bool(node.attribute(name)); }
  /// The attribute's value; throws when it is absent or empty.
  std::string_view required(const char* name) const;
  /// Throws for any attribute not in `allowed`.
  void checkAttributes(std::initializer_list<std::string_view> allowed) const;
  /// The element children, in order; throws on non-whitespace text between them.
  std::vector<XmlElement> children() const;

  template <typename... Args>
  [[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) const {
    throw Error(location() + ": " + fmt::format(format, std::forward<Args>(args)...));
  }
};

/// Parses a finite decimal number; `what` names it in the error.
double parseNumber(const XmlElement& at, std::string_view text, std::string_view what);
/// Parses a whole integer; `what` names it in the error.
long long parseInteger(const XmlElement& at, std::string_view text, std::string_view what);
/// Numbers separated by commas and/or whitespace, as Mitsuba writes vectors and matrices.
std::vector<double> parseNumberList(const XmlElement& at, std::string_view text,
                                    std::string_view what);

/// Replaces every $name in the attributes of `element` and its descendants by params[name];
/// an undefined name throws. Names are the longest run of [A-Za-z0-9_] after '$'.
void substituteParameters(const XmlElement& element,
                          const std::map<std::string, std::string>& params);

}  // namespace quadtri
