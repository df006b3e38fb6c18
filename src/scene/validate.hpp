// Parameter errors: thrown before anything is simulated, with the reason and the offending value.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace beltsim {

struct Parameter;
struct Friction;

struct ParameterError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "what must be > 0 (got value unit)"
[[noreturn]] void reject(const std::string& what, const std::string& rule, double value, const std::string& unit);
// the same for a parameter of the scene's table by its dotted key ("belt.strain"), with the table's unit
[[noreturn]] void reject(std::string_view dotted, const std::string& rule, double value);
void require_positive(const std::string& what, double value, const std::string& unit);
void require_non_negative(const std::string& what, double value, const std::string& unit);
void require_finite(const std::string& what, double value, const std::string& unit);
// a friction coefficient: "" when it is one, else why not (parameters.hpp, kMuMax)
std::string mu_problem(double mu);
void require_mu(const std::string& what, double mu);
// value v of parameter par (scene/parameters.hpp), named `what`, against the parameter's rule
void check_rule(const Parameter& par, const std::string& what, double v);
// a friction law's numbers by the rules of the parameter table's "friction" entries, named
// "<label>.<key>" ("friction.segments[2].static_ratio")
void check_friction_law(const Friction& f, const std::string& label);
inline constexpr size_t kMaxFrictionSegments = 255;  // Model::law_of holds a segment's number in a byte

}  // namespace beltsim
