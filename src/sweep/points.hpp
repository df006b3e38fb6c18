// The points of a sweep (docs/sweeps.md): a grid (every combination of the listed values) or a
// random sample (n points, each parameter uniform in its range, reproducible from a seed). Lua-free:
// the sweep file (script/lua_sweep.hpp) and the command line's --set lists both give one of these.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace beltsim::sweep {

// one parameter's value as the script sees it (p.NAME)
using Value = std::variant<long long, double, bool, std::string>;
// as written to the CSV files: integers as they are, other numbers the shortest decimal that
// reads back as the same double (io/number_text.hpp), true/false, text as it is
std::string value_text(const Value& v);

struct Point {
  int index = 0;   // 0..count-1, the K of --point K and of a Slurm array task
  std::string id;  // the index with leading zeros to the width of the last one: "007" of 120
  std::vector<std::pair<std::string, Value>> params;  // in the sweep's order of names
};

// the point's parameters for messages: "a=1, b=\"x\"" (values as value_text, strings quoted)
std::string params_text(const Point& p);

// names[k] takes the values values[k]; the first name varies slowest, the last fastest
struct Grid {
  std::vector<std::string> names;
  std::vector<std::vector<Value>> values;
};

// n points; names[k] uniform in [ranges[k].first, ranges[k].second)
struct Samples {
  long long n = 0;
  std::vector<std::string> names;
  std::vector<std::pair<double, double>> ranges;
  std::uint64_t seed = 1;
};

std::string point_id(int index, int count);
// "point", "status" and "inputs", the names of the columns point.csv has besides the parameters
// and the figures: no parameter takes one
bool reserved_name(const std::string& name);
// throws std::invalid_argument for an empty grid (a name without values), one of more than
// kMaxPoints points, or a reserved name
std::vector<Point> grid_points(const Grid& g);
// throws std::invalid_argument for n outside 1..kMaxPoints, a range with hi < lo or a reserved name
std::vector<Point> sample_points(const Samples& s);

inline constexpr long long kMaxPoints = 1'000'000;

}  // namespace beltsim::sweep
