// CSV writer: a header row, then one row of numbers per call; '.' decimal point whatever the
// locale, full double precision, NaN written as "nan" (pandas and MATLAB's readtable read it).
// Each row is flushed once at least `flush_interval` seconds have passed and on close, so a run
// that stops for any reason leaves every row it produced on disk.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace beltsim {

class CsvWriter {
 public:
  // append: continue an existing file (a resumed run) without writing the header again
  CsvWriter(const std::string& path, const std::vector<std::string>& header, double flush_interval = 0.5,
            bool append = false);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  void row(const std::vector<double>& values);
  void flush();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  size_t columns_;
  double flush_interval_;
  std::chrono::steady_clock::time_point last_flush_;
};

// one cell: quotes text containing a comma, quote or newline
std::string csv_text(const std::string& s);

}  // namespace beltsim
