// Parameter errors: thrown before anything is simulated, with the reason and the offending value
// (the checks that throw them: scene/validate.hpp; the route's: scene/route.hpp).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "scene/key_path.hpp"

namespace beltsim {

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

}  // namespace beltsim
