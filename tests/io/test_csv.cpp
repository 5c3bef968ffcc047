#include <gtest/gtest.h>

#include "quadtri/io/csv.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parseCsv(text, "in.csv");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Csv, FieldsAreQuotedOnlyWhereNeeded) {
  EXPECT_EQ(csvField("plain text"), "plain text");
  EXPECT_EQ(csvField(""), "");
  EXPECT_EQ(csvField("a,b"), "\"a,b\"");
  EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csvField(" padded"), "\" padded\"");
}

TEST(Csv, ParsesQuotesLineBreaksAndBlankLines) {
  const std::string text =
      "name,path\r\na,\"x, y.obj\"\n\n\"say \"\"hi\"\"\",\"two\nlines\"\nlast,\n";
  const CsvTable t = parseCsv(text, "in.csv");
  ASSERT_EQ(t.rows.size(), 4u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"name", "path"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"a", "x, y.obj"}));
  EXPECT_EQ(t.rows[2], (std::vector<std::string>{"say \"hi\"", "two\nlines"}));
  EXPECT_EQ(t.rows[3], (std::vector<std::string>{"last", ""}));
  EXPECT_EQ(t.line, (std::vector<size_t>{1, 2, 4, 6}));
  // Written fields read back as they were.
  for (const std::string s : {"a,b", "q\"uote", "multi\nline", " lead", ""}) {
    const CsvTable back = parseCsv(csvField(s) + ",end\n", "back.csv");
    ASSERT_EQ(back.rows.size(), 1u) << s;
    EXPECT_EQ(back.rows[0], (std::vector<std::string>{s, "end"})) << s;
  }
  EXPECT_EQ(parseCsv("no newline at the end", "x").rows.size(), 1u);
}

TEST(Csv, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(errorOf("a,b\nc,\"open\n"),
            "in.csv:2: a quoted field is not closed before the end of the file");
  EXPECT_EQ(errorOf("a,b\n\"x\"y,z\n"), "in.csv:2: text after a closing quote");
  EXPECT_EQ(errorOf("a,b\nc,d\"e\n"),
            "in.csv:2: a quote inside an unquoted field (or a second quoted part) of row 2");
}

TEST(Csv, MissingFileIsAnError) {
  EXPECT_THROW(readCsvFile("/nonexistent/quadtri/manifest.csv"), Error);
}

}  // namespace
}  // namespace quadtri
