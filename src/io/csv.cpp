#include "quadtri/io/csv.h"

#include <fstream>
#include <sstream>

#include "quadtri/math/error.h"

namespace quadtri {

std::string csvField(std::string_view text) {
  const bool quote = text.find_first_of(",\"\r\n") != std::string_view::npos ||
                     (!text.empty() && (text.front() == ' ' || text.back() == ' '));
  if (!quote) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

CsvTable parseCsv(std::string_view text, const std::string& source) {
  CsvTable table;
  std::vector<std::string> row;
  std::string field;
  size_t line = 1, rowLine = 1;
  bool inQuotes = false, quoted = false, rowHasText = false;
  auto endField = [&] {
    row.push_back(std::move(field));
    field.clear();
    quoted = false;
  };
  auto endRow = [&] {
    endField();
    // A blank line is one empty unquoted field: skip it.
    if (rowHasText || row.size() > 1 || !row.front().empty()) {
      table.rows.push_back(std::move(row));
      table.line.push_back(rowLine);
    }
    row.clear();
    rowHasText = false;
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inQuotes) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          inQuotes = false;
        }
      } else {
        if (c == '\n') ++line;
        field += c;
      }
      continue;
    }
    if (c == '"') {
      if (quoted || !field.empty())
        fail("{}:{}: a quote inside an unquoted field (or a second quoted part) of row {}", source,
             line, table.rows.size() + 1);
      inQuotes = quoted = rowHasText = true;
    } else if (c == ',') {
      endField();
      rowHasText = true;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      endRow();
      rowLine = ++line;
    } else {
      if (quoted) fail("{}:{}: text after a closing quote", source, line);
      field += c;
    }
  }
  if (inQuotes)
    fail("{}:{}: a quoted field is not closed before the end of the file", source, rowLine);
  if (!field.empty() || !row.empty() || rowHasText) endRow();
  return table;
}

CsvTable readCsvFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot read the file", path.string());
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) fail("{}: read error", path.string());
  return parseCsv(text.str(), path.string());
}

}  // namespace quadtri
