// Comma-separated values (RFC 4180): quoting fields on output, reading a file with quoted
// fields and errors that name the file and line.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace quadtri {

/// `text` as one CSV field: unchanged unless it holds a comma, a quote, a line break or leading
/// or trailing spaces; then in double quotes with every quote doubled.
std::string csvField(std::string_view text);

/// A CSV file read into rows of fields; line[i] is the 1-based line on which row i starts.
struct CsvTable {
  std::vector<std::vector<std::string>> rows;
  std::vector<size_t> line;
};

/// Parses CSV text: fields split on commas, double-quoted fields may hold commas, doubled
/// quotes and line breaks, lines end in LF or CRLF, blank lines are skipped. `source` names the
/// text in errors (an unterminated quote, text after a closing quote), with the line.
CsvTable parseCsv(std::string_view text, const std::string& source);

/// Reads and parses a CSV file; throws Error naming the file when it cannot be read.
CsvTable readCsvFile(const std::filesystem::path& path);

}  // namespace quadtri
