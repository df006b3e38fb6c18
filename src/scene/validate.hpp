// Parameter errors: thrown before anything is simulated, with the reason and the offending value.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene/key_path.hpp"

namespace beltsim {

struct Parameter;
struct Friction;

// What an error is about, as fields for the one who reports it (script/lua_scene.cpp finds the
// line the key was written on from `path`, not from the message's words): the parameter's path
// ("belt.sde.k", "pulley 'driver'.radius", "friction.segments[2].mu"), the reason, and the
// value with its unit when it is a number.
struct ParameterError : std::invalid_argument {
  // about no one parameter ("two pulleys are named 'a'"): the message alone, an empty path
  explicit ParameterError(const std::string& message);
  // about the parameter at `path` (path_text's spelling, scene/key_path.hpp): "path: reason", or
  // "path must be > 0 (got -1 kg/m)" for a rule and a value
  ParameterError(const std::string& path, std::string reason, std::optional<double> value = std::nullopt,
                 std::string unit = "");
  // about the parameter at `path`, in words of its own ("pulleys 'a' and 'b' overlap: ...")
  ParameterError(KeyPath path, const std::string& message);
  KeyPath path;
  std::string reason;
  std::optional<double> value;
  std::string unit;
};

// "path: reason", or "path must be > 0 (got -1 kg/m)" for a rule and a value: the message of an
// error about `path`; numbers through rounded_text (io/number_text.hpp)
std::string parameter_message(const std::string& path, const std::string& reason, std::optional<double> value,
                              const std::string& unit);

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
