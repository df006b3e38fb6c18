#include "sweep/points.hpp"

#include <stdexcept>
#include <type_traits>

#include "io/number_text.hpp"

namespace beltsim::sweep {

std::string value_text(const Value& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, long long>)
          return std::to_string(x);
        else if constexpr (std::is_same_v<T, double>)
          return number_text(x);
        else if constexpr (std::is_same_v<T, bool>)
          return x ? "true" : "false";
        else
          return x;
      },
      v);
}

std::string params_text(const Point& p) {
  // a string quoted, as --set writes one: "300" read as text is not the number 300 the line shows
  std::string s;
  for (const auto& [name, v] : p.params)
    s += (s.empty() ? "" : ", ") + name + "=" +
         (std::holds_alternative<std::string>(v) ? "\"" + value_text(v) + "\"" : value_text(v));
  return s;
}

std::string point_id(int index, int count) {
  const std::size_t width = std::to_string(count > 1 ? count - 1 : 0).size();
  std::string s = std::to_string(index);
  return std::string(s.size() < width ? width - s.size() : 0, '0') + s;
}

bool reserved_name(const std::string& name) {
  return name == "point" || name == "status" || name == "inputs";
}

namespace {

// throws std::invalid_argument naming what.NAME when a name is reserved
void check_names(const std::vector<std::string>& names, const std::string& what) {
  for (const std::string& n : names)
    if (reserved_name(n))
      throw std::invalid_argument(
          what + "." + n + ": a parameter may not be named '" + n +
          "': point.csv has a column of that name (point, status and inputs are taken); give it another");
}

}  // namespace

std::vector<Point> grid_points(const Grid& g) {
  check_names(g.names, "grid");
  long long count = 1;
  for (std::size_t k = 0; k < g.names.size(); ++k) {
    if (g.values[k].empty()) throw std::invalid_argument("grid." + g.names[k] + ": no values");
    count *= static_cast<long long>(g.values[k].size());
    if (count > kMaxPoints)
      throw std::invalid_argument("the grid has more than " + std::to_string(kMaxPoints) + " points");
  }
  if (g.names.empty()) throw std::invalid_argument("the grid names no parameter");
  std::vector<Point> out(static_cast<std::size_t>(count));
  for (long long i = 0; i < count; ++i) {
    Point& p = out[static_cast<std::size_t>(i)];
    p.index = static_cast<int>(i);
    p.id = point_id(p.index, static_cast<int>(count));
    p.params.resize(g.names.size());
    long long rest = i;
    for (std::size_t k = g.names.size(); k-- > 0;) {  // the last name fastest
      const auto n = static_cast<long long>(g.values[k].size());
      p.params[k] = {g.names[k], g.values[k][static_cast<std::size_t>(rest % n)]};
      rest /= n;
    }
  }
  return out;
}

namespace {

// splitmix64 (Steele, Lea and Flood 2014): the same sequence on every machine and compiler,
// unlike the distributions of <random>
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

std::vector<Point> sample_points(const Samples& s) {
  if (s.n < 1 || s.n > kMaxPoints)
    throw std::invalid_argument("samples.n: must be a whole number in 1.." + std::to_string(kMaxPoints) + " (got " +
                                std::to_string(s.n) + ")");
  if (s.names.empty()) throw std::invalid_argument("samples.ranges names no parameter");
  check_names(s.names, "samples.ranges");
  for (std::size_t k = 0; k < s.names.size(); ++k)
    if (!(s.ranges[k].first <= s.ranges[k].second))
      throw std::invalid_argument("samples.ranges." + s.names[k] + ": {lo, hi} with lo <= hi expected (got {" +
                                  number_text(s.ranges[k].first) + ", " + number_text(s.ranges[k].second) + "})");
  std::vector<Point> out(static_cast<std::size_t>(s.n));
  std::uint64_t state = s.seed;
  for (long long i = 0; i < s.n; ++i) {
    Point& p = out[static_cast<std::size_t>(i)];
    p.index = static_cast<int>(i);
    p.id = point_id(p.index, static_cast<int>(s.n));
    for (std::size_t k = 0; k < s.names.size(); ++k) {
      const double u = static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53;  // [0, 1)
      const auto [lo, hi] = s.ranges[k];
      p.params.emplace_back(s.names[k], lo + (hi - lo) * u);
    }
  }
  return out;
}

}  // namespace beltsim::sweep
