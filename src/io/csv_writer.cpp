#include "io/csv_writer.hpp"

#include <stdexcept>


namespace beltsim {

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string cur;
  bool quoted = false, begun = false;  // begun: the row has a character (the last row needs no \n)
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        cur += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cur += c;
      }
      continue;
    }
    begun = c != '\n';
    if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(std::move(cur));
      cur.clear();
    } else if (c == '\n') {
      row.push_back(std::move(cur));
      cur.clear();
      rows.push_back(std::move(row));
      row.clear();
    } else {
      cur += c;
    }
  }
  if (begun || quoted) {
    row.push_back(std::move(cur));
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::vector<std::string>> rows = csv_rows(line);
  return rows.empty() ? std::vector<std::string>{""} : std::move(rows.front());
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& header, bool append)
    : file_(path, append), columns_(header.size()) {
  start(header, append);
}

CsvWriter::CsvWriter(const OutputDir& dir, const std::string& name, const std::vector<std::string>& header,
                     bool append)
    : file_(dir, name, append), columns_(header.size()) {
  start(header, append);
}

std::string csv_header(const std::vector<std::string>& names) {
  std::string line;
  for (size_t k = 0; k < names.size(); ++k) {
    if (k) line += ',';
    line += csv_text(names[k]);
  }
  return line;
}

void CsvWriter::start(const std::vector<std::string>& header, bool append) {
  if (append) return;
  line_ = csv_header(header) + '\n';
  file_.write(line_);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_) throw std::logic_error("CsvWriter: row width differs from the header");
  line_.clear();
  for (size_t k = 0; k < values.size(); ++k) {
    if (k) line_ += ',';
    append_value(line_, values[k]);
  }
  line_ += '\n';
  file_.write(line_);
}

}  // namespace beltsim
