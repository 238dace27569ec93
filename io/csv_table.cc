#include "io/csv_table.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace moorsim::output {

std::string_view WithoutByteOrderMark(std::string_view first_line) {
  constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";
  if (first_line.substr(0, kUtf8ByteOrderMark.size()) == kUtf8ByteOrderMark) {
    first_line.remove_prefix(kUtf8ByteOrderMark.size());
  }
  return first_line;
}

CsvTable ReadCsvTable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (!in) throw InputError(path + ": cannot read it");
  const std::string whole = buffer.str();
  const std::string_view text = WithoutByteOrderMark(whole);
  if (text.empty()) throw InputError(path + ": empty (no header line)");
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    const auto line = 1 + std::count(text.begin(), text.begin() + nul, '\n');
    throw InputError(path + ":" + std::to_string(line) + ": a NUL byte (not a text table)");
  }

  CsvTable table;
  std::vector<std::string> record;
  std::string field;
  std::size_t line = 1;
  std::size_t record_line = 1;
  const auto end_record = [&] {
    record.push_back(std::move(field));
    field.clear();
    if (table.header.empty() && table.rows.empty()) {
      table.header = std::move(record);
    } else if (record.size() != table.header.size()) {
      throw InputError(path + ":" + std::to_string(record_line) + ": " +
                       std::to_string(record.size()) + " fields, the header has " +
                       std::to_string(table.header.size()));
    } else {
      table.rows.push_back(std::move(record));
      table.row_lines.push_back(record_line);
    }
    record.clear();
  };
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '"' && field.empty()) {
      const std::size_t quote_line = line;
      for (++i;; ++i) {
        if (i >= text.size()) {
          throw InputError(path + ":" + std::to_string(quote_line) + ": a quote never closed");
        }
        if (text[i] == '"') {
          if (i + 1 < text.size() && text[i + 1] == '"') {
            field += '"';
            ++i;
            continue;
          }
          ++i;
          break;
        }
        if (text[i] == '\n') ++line;
        field += text[i];
      }
      continue;
    }
    if (c == ',') {
      record.push_back(std::move(field));
      field.clear();
    } else if (c == '\n' || (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n')) {
      if (c == '\r') ++i;
      end_record();
      ++line;
      record_line = line;
    } else {
      field += c;
    }
    ++i;
  }
  // A last record without its line break.
  if (!field.empty() || !record.empty()) end_record();
  return table;
}

}  // namespace moorsim::output
