// CSV writer: a header row, then one row of numbers per call; '.' decimal point whatever the
// locale, each number the shortest decimal that reads back as the same double (std::to_chars:
// full round-trip precision, shorter than %.17g), NaN written as "nan" (pandas and MATLAB's
// readtable read it).
// Each row is assembled in memory and written whole by one write(2) (io/row_file.hpp), so the
// file holds every row produced so far and only whole rows, whatever stops the process.
#pragma once

#include <string>
#include <vector>

#include "io/number_text.hpp"  // each number as number_text writes it
#include "io/row_file.hpp"

namespace beltsim {

class CsvWriter {
 public:
  // append: continue an existing file (a resumed run) without writing the header again; the
  // file's missing folders are made (io/output_dir.hpp, output_place). Throws std::runtime_error
  // naming the file and the reason (here and in row()).
  CsvWriter(const std::string& path, const std::vector<std::string>& header, bool append = false);
  // DIR/NAME (io/output_dir.hpp: never through a link)
  CsvWriter(const OutputDir& dir, const std::string& name, const std::vector<std::string>& header, bool append);
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  void row(const std::vector<double>& values);
  const std::string& path() const { return file_.path(); }
  RowFile& file() { return file_; }  // (its bytes' hash)
  const RowFile& file() const { return file_; }

 private:
  void start(const std::vector<std::string>& header, bool append);
  RowFile file_;
  size_t columns_;
  std::string line_;  // the row being assembled (its capacity reused)
};

// one cell: quotes text containing a comma, quote, line feed or carriage return
std::string csv_text(const std::string& s);
// the header line of those column names, as CsvWriter writes it (without its line end)
std::string csv_header(const std::vector<std::string>& names);
// the rows of a CSV text, each a line's cells with csv_text's quoting undone
// ("a,\"b,\"\"c\"\"\"" is a and b,"c"); a quoted cell may hold line breaks; the last row may end
// without one
std::vector<std::vector<std::string>> csv_rows(const std::string& text);
// the cells of one line (csv_rows' first row; "" gives one empty cell)
std::vector<std::string> csv_fields(const std::string& line);

}  // namespace beltsim
