// Reading a CSV table, such as the runs.csv of `moorsim batch`: a header line of column
// names, then one record per line. RFC 4180 quoting: a field in double quotes may hold
// commas, line breaks and doubled quotes (""); lines may end in CRLF.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace moorsim::output {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  ///< one field per header column
  std::vector<std::size_t> row_lines;          ///< the line each row starts on (1-based)
};

/// Reads the CSV file `path`. Throws InputError "<path>: ..." if it cannot be read, is
/// empty or holds a NUL byte (a binary file), "<path>:<line>: ..." for a record whose
/// number of fields differs from the header's or a quote that is never closed.
CsvTable ReadCsvTable(const std::string& path);

}  // namespace moorsim::output
