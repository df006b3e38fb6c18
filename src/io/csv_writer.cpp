#include "io/csv_writer.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace beltsim {

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& header, double flush_interval,
                     bool append)
    : path_(path), columns_(header.size()), flush_interval_(flush_interval) {
  f_ = std::fopen(path.c_str(), append ? "a" : "w");
  if (!f_) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  last_flush_ = std::chrono::steady_clock::now();
  if (append) return;
  for (size_t k = 0; k < header.size(); ++k) std::fprintf(f_, "%s%s", k ? "," : "", csv_text(header[k]).c_str());
  std::fputc('\n', f_);
  std::fflush(f_);
  last_flush_ = std::chrono::steady_clock::now();
}

CsvWriter::~CsvWriter() {
  if (f_) std::fclose(f_);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_) throw std::logic_error("CsvWriter: row width differs from the header");
  char buf[32];
  for (size_t k = 0; k < values.size(); ++k) {
    const double v = values[k];
    if (std::isnan(v)) {
      std::snprintf(buf, sizeof buf, "nan");
    } else {
      std::snprintf(buf, sizeof buf, "%.10g", v);  // %g never uses the locale's decimal comma here:
    }                                              // the C locale is in force (no setlocale call)
    if (k) std::fputc(',', f_);
    std::fputs(buf, f_);
  }
  std::fputc('\n', f_);
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_flush_).count() >= flush_interval_) {
    std::fflush(f_);
    last_flush_ = now;
  }
}

void CsvWriter::flush() {
  if (f_) std::fflush(f_);
}

}  // namespace beltsim
