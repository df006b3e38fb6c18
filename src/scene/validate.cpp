#include "scene/validate.hpp"

#include <cmath>
#include <sstream>

namespace beltsim {

void reject(const std::string& what, const std::string& rule, double value, const std::string& unit) {
  std::ostringstream s;
  s.precision(6);
  s << what << ' ' << rule << " (got " << value << (unit.empty() ? "" : " ") << unit << ")";
  throw ParameterError(s.str());
}

void require_finite(const std::string& what, double value, const std::string& unit) {
  if (!std::isfinite(value)) reject(what, "must be a finite number", value, unit);
}

void require_positive(const std::string& what, double value, const std::string& unit) {
  require_finite(what, value, unit);
  if (!(value > 0)) reject(what, "must be > 0", value, unit);
}

void require_non_negative(const std::string& what, double value, const std::string& unit) {
  require_finite(what, value, unit);
  if (!(value >= 0)) reject(what, "must be >= 0", value, unit);
}

}  // namespace beltsim
