// The one CSV reader (src/io/csv.cpp, RFC 4180): cells of a record, records over several lines, the
// numeric column reader on quoted headers, the writer's quoting read back, malformed records named by
// file and line.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "test_support.hpp"

using namespace rootsim;
using Cells = std::vector<std::string>;

TEST_CASE("csv: a record's cells - plain and quoted fields with commas and doubled quotes") {
  CHECK(csvCells("a,b,c") == Cells{"a", "b", "c"});
  CHECK(csvCells("") == Cells{""});
  CHECK(csvCells("a,") == Cells{"a", ""});
  CHECK(csvCells(",") == Cells{"", ""});
  CHECK(csvCells("\"x,y\",2") == Cells{"x,y", "2"});
  CHECK(csvCells("\"say \"\"hi\"\"\",\"\"") == Cells{"say \"hi\"", ""});
  CHECK(csvCells("\"line\none\",3") == Cells{"line\none", "3"});
  // a quote inside an unquoted field is an ordinary character (as spreadsheets read it)
  CHECK(csvCells("5\" pot,1") == Cells{"5\" pot", "1"});
}

TEST_CASE("csv: a malformed record - an open quote or text after a closing quote") {
  CHECK_THROWS_WITH_AS(csvCells("\"open,1"), doctest::Contains("not closed"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(csvCells("\"a\"b,1"), doctest::Contains("text after a quoted field's closing quote (cell 1)"),
                       std::invalid_argument);
}

TEST_CASE("csv: what csvField and csvQuoted write reads back as the same text") {
  const std::vector<std::string> texts = {"plain", "with,comma", "with \"quote\"", "two\nlines", "", "\"", ",,"};
  std::string row;
  for (const std::string& t : texts) row += (row.empty() ? "" : ",") + csvField(t);
  CHECK(csvCells(row) == texts);
  row.clear();
  for (const std::string& t : texts) row += (row.empty() ? "" : ",") + csvQuoted(t);
  CHECK(csvCells(row) == texts);
  CHECK(csvField("plain") == "plain");
  CHECK(csvQuoted("plain") == "\"plain\"");
  CHECK(csvQuoted("a\"b") == "\"a\"\"b\"");
}

TEST_CASE("csv: records over several lines - line numbers and CRLF and an unclosed quote at the end") {
  std::istringstream in("name,note\r\nA,\"two\nlines\"\r\nB,plain\n");
  Cells f;
  int line = 0;
  REQUIRE(readCsvRecord(in, f, line, "t.csv"));
  CHECK(f == Cells{"name", "note"});
  CHECK(line == 1);
  REQUIRE(readCsvRecord(in, f, line, "t.csv"));
  CHECK(f == Cells{"A", "two\nlines"});
  CHECK(line == 3);
  REQUIRE(readCsvRecord(in, f, line, "t.csv"));
  CHECK(f == Cells{"B", "plain"});
  CHECK(line == 4);
  CHECK_FALSE(readCsvRecord(in, f, line, "t.csv"));

  std::istringstream open("a,b\n1,\"never\nclosed\n");
  line = 0;
  REQUIRE(readCsvRecord(open, f, line, "open.csv"));
  CHECK_THROWS_WITH_AS(readCsvRecord(open, f, line, "open.csv"),
                       doctest::Contains("open.csv:2: a quoted field is not closed before the end of the file"), SceneError);
  std::istringstream after("a,b\n\"x\"y,1\n");
  line = 0;
  REQUIRE(readCsvRecord(after, f, line, "after.csv"));
  CHECK_THROWS_WITH_AS(readCsvRecord(after, f, line, "after.csv"), doctest::Contains("after.csv:2: text after"), SceneError);
}

TEST_CASE("csv: readCsvColumns reads a quoted header and names a bad cell by file and line") {
  const auto d = test::scratchDir("csv", "columns");
  {
    std::ofstream f(d / "q.csv");
    f << "\"a,1\",\"b \"\"x\"\"\"\r\n1,2\r\n\r\n3.5,-4\r\n";
  }
  const CsvColumns c = readCsvColumns(d / "q.csv");
  CHECK(c.names == Cells{"a,1", "b \"x\""});
  REQUIRE(c.values.size() == 2);
  CHECK(c.values[0] == std::vector<double>{1, 3.5});
  CHECK(c.values[1] == std::vector<double>{2, -4});
  {
    std::ofstream f(d / "bad.csv");
    f << "a,b\n1,\"2\n\"x\n";
  }
  CHECK_THROWS_WITH_AS(readCsvColumns(d / "bad.csv"), doctest::Contains("bad.csv:3: text after"), SceneError);
}
