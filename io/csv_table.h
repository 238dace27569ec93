// Reading a CSV table, such as the runs.csv of `moorsim batch`: a header line of column
// names, then one record per line. RFC 4180 quoting: a field in double quotes may hold
// commas, line breaks and doubled quotes (""); lines may end in CRLF; a UTF-8 byte-order
// mark before the header (Excel writes one) is skipped.
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
/// Every CSV reader of moorsim (this one, `moorsim detect`'s) takes the header through it.
std::string_view WithoutByteOrderMark(std::string_view first_line);

}  // namespace moorsim::output
