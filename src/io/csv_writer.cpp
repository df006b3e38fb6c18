#include "io/csv_writer.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace beltsim {

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& header, double /*flush_interval*/,
                     bool append)
    : file_(path, append), columns_(header.size()) {
  if (append) return;
  for (size_t k = 0; k < header.size(); ++k) {
    if (k) line_ += ',';
    line_ += csv_text(header[k]);
  }
  line_ += '\n';
  file_.write(line_);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_) throw std::logic_error("CsvWriter: row width differs from the header");
  line_.clear();
  char buf[32];
  for (size_t k = 0; k < values.size(); ++k) {
    const double v = values[k];
    // %g never uses the locale's decimal comma here: the C locale is in force (no setlocale call)
    const int n = std::isnan(v) ? std::snprintf(buf, sizeof buf, "nan") : std::snprintf(buf, sizeof buf, "%.10g", v);
    if (k) line_ += ',';
    line_.append(buf, static_cast<size_t>(n));
  }
  line_ += '\n';
  file_.write(line_);
}

}  // namespace beltsim
