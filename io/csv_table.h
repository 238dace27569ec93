// CSV tables as moorsim reads and writes them (runs.csv of `moorsim batch`, alarms.csv of
// `moorsim detect`, pose logs): a header line of column names, then one record per line.
// RFC 4180 quoting: a field in double quotes may hold commas, line breaks and doubled
// quotes (""); lines may end in CRLF; a UTF-8 byte-order mark before the header (Excel
// writes one) is skipped. Every CSV reader and writer of moorsim goes through this file.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace moorsim::output {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  ///< one field per header column
  std::vector<std::size_t> row_lines;          ///< the line each row starts on (1-based)
};

/// Reads the CSV file `path`. Throws InputError "<path>: ..." if it cannot be read or is
/// empty, "<path>:<line>: ..." for a NUL byte (a binary file), a record whose number of
/// fields differs from the header's or a quote that is never closed.
CsvTable ReadCsvTable(const std::string& path);

/// `first_line` (the start of a CSV file) without its UTF-8 byte-order mark, if it has one.
std::string_view WithoutByteOrderMark(std::string_view first_line);

/// The fields of one record that fits on one line (no line break inside quotes), as a
/// streamed reader takes them line by line: `line` without its line break. Quoted fields
/// are unquoted; unquoted fields are returned as written. Throws InputError "<where>: a
/// quote never closed" for an unbalanced quote.
std::vector<std::string> SplitCsvRecord(std::string_view line, const std::string& where);

/// `text` as one CSV field: as it is, or in double quotes (inner quotes doubled) when it
/// holds a comma, a quote or a line break.
std::string CsvField(std::string_view text);

}  // namespace moorsim::output
