#include "xml_file.h"

#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace quadtri {

XmlFile::XmlFile(std::string_view text, std::filesystem::path path) : path_(std::move(path)) {
  lineStarts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') lineStarts_.push_back(i + 1);
  const pugi::xml_parse_result result =
      doc_.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!result)
    fail("{}:{}: XML syntax error: {}", path_.string(), lineOf(result.offset),
         result.description());
  if (!doc_.document_element()) fail("{}:1: no root element", path_.string());
  // The scene's readers walk elements recursively: a nesting deeper than any scene needs is
  // refused here, by an iterative walk, before it can overflow their stack.
  std::vector<std::pair<pugi::xml_node, int>> stack{{doc_.document_element(), 1}};
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    if (depth > kMaxXmlDepth)
      fail("{}:{}: elements nest deeper than {} levels", path_.string(),
           lineOf(node.offset_debug()), kMaxXmlDepth);
    for (pugi::xml_node child : node.children())
      if (child.type() == pugi::node_element) stack.emplace_back(child, depth + 1);
  }
}

size_t XmlFile::lineOf(ptrdiff_t offset) const {
  if (offset < 0) return 1;
  const auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), size_t(offset));
  return size_t(it - lineStarts_.begin());
}

std::string XmlElement::location() const {
  return fmt::format("{}:{}", file->path().string(), file->lineOf(node.offset_debug()));
}

std::string_view XmlElement::required(const char* name) const {
  const std::string_view value = attr(name);
  if (value.empty()) fail("<{}> needs a non-empty '{}' attribute", tag(), name);
  return value;
}

void XmlElement::checkAttributes(std::initializer_list<std::string_view> allowed) const {
  for (const pugi::xml_attribute a : node.attributes())
    if (std::find(allowed.begin(), allowed.end(), std::string_view(a.name())) == allowed.end())
      fail("unknown attribute '{}' on <{}>; expected {}", a.name(), tag(),
           fmt::join(allowed, ", "));
}

std::vector<XmlElement> XmlElement::children() const {
  std::vector<XmlElement> out;
  for (const pugi::xml_node child : node.children()) {
    if (child.type() == pugi::node_element) {
      out.push_back({file, child});
    } else if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
      // parse_default already drops whitespace-only text, so anything left is content.
      XmlElement{file, child}.fail("unexpected text '{}' inside <{}>", child.value(), tag());
    }
  }
  return out;
}

namespace {

std::string_view trim(std::string_view s) {
  const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

}  // namespace

double parseNumber(const XmlElement& at, std::string_view text, std::string_view what) {
  const std::string_view t = trim(text);
  // from_chars rejects a leading '+', which XML writers do emit.
  const std::string_view digits = !t.empty() && t.front() == '+' ? t.substr(1) : t;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
    at.fail("{}: '{}' is not a number", what, text);
  if (!std::isfinite(value)) at.fail("{}: '{}' is not a finite number", what, text);
  return value;
}

long long parseInteger(const XmlElement& at, std::string_view text, std::string_view what) {
  const std::string_view t = trim(text);
  const std::string_view digits = !t.empty() && t.front() == '+' ? t.substr(1) : t;
  long long value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
    at.fail("{}: '{}' is not an integer", what, text);
  return value;
}

std::vector<double> parseNumberList(const XmlElement& at, std::string_view text,
                                    std::string_view what) {
  std::vector<double> values;
  size_t i = 0;
  const auto isSeparator = [](char c) {
    return c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r';
  };
  while (i < text.size()) {
    while (i < text.size() && isSeparator(text[i])) ++i;
    size_t j = i;
    while (j < text.size() && !isSeparator(text[j])) ++j;
    if (j > i) values.push_back(parseNumber(at, text.substr(i, j - i), what));
    i = j;
  }
  return values;
}

void substituteParameters(const XmlElement& element,
                          const std::map<std::string, std::string>& params) {
  const auto isNameChar = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  };
  for (pugi::xml_attribute a : element.node.attributes()) {
    const std::string_view value = a.value();
    if (value.find('$') == std::string_view::npos) continue;
    std::string out;
    for (size_t i = 0; i < value.size();) {
      if (value[i] != '$') {
        out += value[i++];
        continue;
      }
      size_t j = i + 1;
      while (j < value.size() && isNameChar(value[j])) ++j;
      const std::string name(value.substr(i + 1, j - i - 1));
      if (name.empty()) element.fail("attribute '{}': '$' must be followed by a name", a.name());
      const auto it = params.find(name);
      if (it == params.end())
        element.fail("attribute '{}' uses ${}, which no <default> or -D defines", a.name(), name);
      out += it->second;
      i = j;
    }
    a.set_value(out.c_str());
  }
  for (const XmlElement& child : element.children()) substituteParameters(child, params);
}

}  // namespace quadtri
