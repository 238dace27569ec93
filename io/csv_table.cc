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

namespace {

// Reads the record that starts at text[*i] (line *line, 1-based; 0 when `where` already
// names the line) into `fields`; on return *i is past its line break and *line counts the
// lines it spanned. `where` names the input in messages.
void ParseRecord(std::string_view text, std::size_t* i, std::size_t* line,
                 std::vector<std::string>* fields, const std::string& where) {
  fields->clear();
  std::string field;
  while (*i < text.size()) {
    const char c = text[*i];
    if (c == '"' && field.empty()) {
      const std::size_t quote_line = *line;
      for (++*i;; ++*i) {
        if (*i >= text.size()) {
          throw InputError(where + (quote_line > 0 ? ":" + std::to_string(quote_line) : "") +
                           ": a quote never closed");
        }
        if (text[*i] == '"') {
          if (*i + 1 < text.size() && text[*i + 1] == '"') {
            field += '"';
            ++*i;
            continue;
          }
          ++*i;
          break;
        }
        if (text[*i] == '\n') ++*line;
        field += text[*i];
      }
      continue;
    }
    if (c == ',') {
      fields->push_back(std::move(field));
      field.clear();
    } else if (c == '\n' || (c == '\r' && *i + 1 < text.size() && text[*i + 1] == '\n')) {
      *i += c == '\r' ? 2 : 1;
      ++*line;
      fields->push_back(std::move(field));
      return;
    } else {
      field += c;
    }
    ++*i;
  }
  fields->push_back(std::move(field));
}

}  // namespace

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
  std::size_t i = 0;
  std::size_t line = 1;
  ParseRecord(text, &i, &line, &table.header, path);
  while (i < text.size()) {
    const std::size_t record_line = line;
    ParseRecord(text, &i, &line, &record, path);
    if (record.size() != table.header.size()) {
      throw InputError(path + ":" + std::to_string(record_line) + ": " +
                       std::to_string(record.size()) + " fields, the header has " +
                       std::to_string(table.header.size()));
    }
    table.rows.push_back(record);
    table.row_lines.push_back(record_line);
  }
  return table;
}

std::vector<std::string> SplitCsvRecord(std::string_view line, const std::string& where) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  std::size_t line_number = 0;
  ParseRecord(line, &i, &line_number, &fields, where);
  return fields;
}

std::string CsvField(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace moorsim::output
