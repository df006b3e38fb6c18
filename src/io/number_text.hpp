// Numbers as text, one way for every file beltsim writes (the CSV files, checkpoints): the
// shortest decimal that reads back as the same double (std::to_chars), with '.' as the decimal
// point whatever the locale; "nan" for every NaN (its sign and payload are not kept), "inf" and
// "-inf". parse_number reads exactly that text back, and nothing looser.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace beltsim {

void append_number(std::string& out, double v);
std::string number_text(double v);
// a value in a results file (timeseries.csv, snapshots.csv): as append_number, with -0 written as
// 0 (a quantity that is zero has no sign for a reader; checkpoints keep it, append_number)
void append_value(std::string& out, double v);
// the same as a string: every number of parameters.csv and events.csv
std::string value_text(double v);

// v rounded to that many significant digits (as printf's %.<digits>g, '.' whatever the locale),
// for messages, where a reader wants "0.1" rather than every digit of the double; "nan" for every
// NaN, as number_text
std::string rounded_text(double v, int digits = 10);

// the whole of s as one decimal number ("1", "-2.5e-3", "inf", "-inf", "nan"): no blanks, no
// leading '+', no hex, nothing after it; nullopt otherwise. Out-of-range magnitudes (1e999) are
// refused rather than rounded to infinity or zero.
std::optional<double> parse_number(std::string_view s);

}  // namespace beltsim
