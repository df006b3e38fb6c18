#include "scene/parameter_error.hpp"

#include "io/number_text.hpp"

namespace beltsim {

std::string parameter_message(const std::string& path, const std::string& reason, std::optional<double> value,
                              const std::string& unit) {
  std::string m = path;
  if (!value) return m.append(": ").append(reason);
  return m.append(" ")
      .append(reason)
      .append(" (got ")
      .append(rounded_text(*value, 6))
      .append(unit.empty() ? "" : " ")
      .append(unit)
      .append(")");
}

ParameterError::ParameterError(const std::string& message) : std::invalid_argument(message), reason(message) {}

ParameterError::ParameterError(KeyPath path_, const std::string& message)
    : std::invalid_argument(message), path(std::move(path_)), reason(message) {}

ParameterError::ParameterError(const std::string& path_, std::string reason_, std::optional<double> value_,
                               std::string unit_)
    : std::invalid_argument(parameter_message(path_, reason_, value_, unit_)),
      path(parse_path(path_)),
      reason(std::move(reason_)),
      value(value_),
      unit(std::move(unit_)) {}

}  // namespace beltsim
