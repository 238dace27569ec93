// Tests of the CSV reader and writer (io/csv_table.h): RFC 4180 quoting, the line each
// row starts on, the errors of tables that are not tables, and fields that read back as
// written.
#include "io/csv_table.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::output {
namespace {

class CsvTableTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = moorsim::testing::FreshDirectory("csv_table_test"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Write(const std::string& text) {
    const std::string path = (dir_ / "t.csv").string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  /// The InputError's message of reading `text`, or "" if it reads.
  std::string ErrorOf(const std::string& text) {
    const std::string path = Write(text);
    try {
      ReadCsvTable(path);
    } catch (const InputError& e) {
      const std::string message = e.what();
      return message.substr(0, path.size()) == path ? message.substr(path.size()) : message;
    }
    return "";
  }

  std::filesystem::path dir_;
};

TEST_F(CsvTableTest, QuotedFieldsHoldCommasQuotesAndLineBreaks) {
  const CsvTable t =
      ReadCsvTable(Write("run,command,error\r\n"
                         "0,\"moorsim run \"\"a,b.yaml\"\"\",\r\n"
                         "1,\"two\nlines\",\"\"\n"
                         "2,plain,last without a line break"));
  EXPECT_EQ(t.header, (std::vector<std::string>{"run", "command", "error"}));
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"0", "moorsim run \"a,b.yaml\"", ""}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"1", "two\nlines", ""}));
  EXPECT_EQ(t.rows[2], (std::vector<std::string>{"2", "plain", "last without a line break"}));
  // The second row spans lines 3 and 4.
  EXPECT_EQ(t.row_lines, (std::vector<std::size_t>{2, 3, 5}));
}

TEST_F(CsvTableTest, WhatIsNotATableIsAnErrorThatPlacesIt) {
  EXPECT_EQ(ErrorOf(""), ": empty (no header line)");
  EXPECT_EQ(ErrorOf(std::string("run\n0\0\n", 7)), ":2: a NUL byte (not a text table)");
  EXPECT_EQ(ErrorOf("run,a\n0,\"x\ny\"\n1\n"), ":4: 1 fields, the header has 2");
  EXPECT_EQ(ErrorOf("run,a\n0,1\n1,\"open\n"), ":3: a quote never closed");
  EXPECT_EQ(ErrorOf("run,a\n0,1\n"), "");
  EXPECT_EQ(ErrorOf("run,a\n\n"), ":2: 1 fields, the header has 2");  // an empty line
}

TEST_F(CsvTableTest, AByteOrderMarkBeforeTheHeaderIsSkipped) {
  // Excel's "CSV UTF-8" starts the file with one; the first column keeps its name.
  const CsvTable t = ReadCsvTable(Write("\xEF\xBB\xBFrun,a\n0,1\n"));
  EXPECT_EQ(t.header, (std::vector<std::string>{"run", "a"}));
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(ErrorOf("\xEF\xBB\xBF"), ": empty (no header line)");
  // Only at the start: elsewhere the bytes are a field's text.
  EXPECT_EQ(ReadCsvTable(Write("run,a\n0,\xEF\xBB\xBF"
                               "1\n"))
                .rows[0][1],
            "\xEF\xBB\xBF"
            "1");
}

TEST(CsvField, QuotesOnlyWhatNeedsItAndReadsBackAsWritten) {
  EXPECT_EQ(CsvField("plain text"), "plain text");
  EXPECT_EQ(CsvField("a,b"), "\"a,b\"");
  EXPECT_EQ(CsvField("say \"x\""), "\"say \"\"x\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
  // Written fields read back as the same record, by the streamed reader and the table's.
  const std::vector<std::string> fields = {"cells, fused", "line \"6\"", "", "3.5"};
  std::string line;
  for (const std::string& f : fields) {
    if (!line.empty()) line += ',';
    line += CsvField(f);
  }
  EXPECT_EQ(SplitCsvRecord(line, "log.csv:2"), fields);
}

TEST(SplitCsvRecord, TakesOneLinesFieldsAndPlacesAnOpenQuote) {
  EXPECT_EQ(SplitCsvRecord("1,2,,x", "w"), (std::vector<std::string>{"1", "2", "", "x"}));
  EXPECT_EQ(SplitCsvRecord("", "w"), (std::vector<std::string>{""}));
  try {
    SplitCsvRecord("1,\"open", "log.csv:7");
    FAIL() << "an open quote was read";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "log.csv:7: a quote never closed");
  }
}

}  // namespace
}  // namespace moorsim::output
