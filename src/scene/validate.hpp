// The checks of a scene's parameters, each throwing a ParameterError (scene/parameter_error.hpp)
// with the reason and the offending value: the helpers, a law's (validate_law) and a whole
// SceneDef's (validate).
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene/parameter_error.hpp"

namespace beltsim {

struct Parameter;
struct Friction;
struct SceneDef;
struct TimeSpeedLaw;

// "what must be > 0 (got value unit)"
[[noreturn]] void reject(const std::string& what, const std::string& rule, double value, const std::string& unit);
// the same for a parameter of the scene's table by its dotted key ("belt.strain"), with the table's unit
[[noreturn]] void reject(std::string_view dotted, const std::string& rule, double value);
void require_positive(const std::string& what, double value, const std::string& unit);
void require_non_negative(const std::string& what, double value, const std::string& unit);
void require_finite(const std::string& what, double value, const std::string& unit);
// a friction coefficient: "" when it is one, else why not (parameters.hpp, kMuMax)
std::string mu_problem(double mu);
// as mu_problem, with the value and the element it was given for: "must be in [0, 10]: ... (got -1
// for element 5)" (sim:wet, sim:set_mu, the live view's wet stretch)
std::string mu_problem(double mu, int element);
void require_mu(const std::string& what, double mu);
// "" when belt.rib_angle (degrees) is a V-rib's included angle (kRibAngleMin..kRibAngleMax), else
// why not: "belt.rib_angle = 0.698° is no V-rib's included angle (20° to 60°; PK belts: 40°): the
// angle is in degrees, not radians (0.698 rad is 40°)", the hint when it is below kRadiansBelow
std::string rib_angle_problem(double degrees);
// value v of parameter par (scene/parameters.hpp), named `what`, against the parameter's rule
void check_rule(const Parameter& par, const std::string& what, double v);
// a friction law's numbers by the rules of the parameter table's "friction" entries, named
// "<label>.<key>" ("friction.segments[2].static_ratio")
void check_friction_law(const Friction& f, const std::string& label);
// Same checks as build_scene's, without building (used by the builder; exposed for tests).
void validate(const SceneDef& def);
// a torque law [N·m] (speed = false) or a prescribed speed [rad/s]: every value finite, tables
// increasing, ramps forward; a speed cannot depend on the speed. Throws ParameterError naming `what`.
void validate_law(const std::string& what, const TimeSpeedLaw& law, bool speed);
// a law made by a helper ("beltsim.ramp", "beltsim.step", "beltsim.sine"): only what its use does
// not change (its times, a sine's frequency and phase), named "<helper>.<key>". Its values are a
// torque's or a speed's by the key it is given to, so validate_law checks them there, in their unit
// (a helper named N·m for a speed's NaN before).
void validate_helper_law(const std::string& helper, const TimeSpeedLaw& law);
inline constexpr size_t kMaxFrictionSegments = 255;

// How the belt's tension at rest was given and the strain at rest it gives, for the checks of its
// size against a belt's (kStrainWarn, kStrainMax: scene/parameters.hpp)
struct StrainAtRest {
  std::string key;     // how it was given: "belt.pretension", "belt.rest_length", "belt.strain"
  double value = 0;    // the value given, in `unit`
  std::string unit;    // "N", "m", ""
  double strain = 0;   // route pitch length / rest length - 1 (for a pretension: T/EA, before the build)
  double tension = 0;  // [N] the spans' tension at rest (0: not known yet)
  double EA = 0;       // [N] the belt's axial rigidity (per SDE values: k·l0)
  double route = 0;    // [m] the route's pitch length
};
// Throws (ParameterError naming s.key and s.value) when the strain reaches kStrainMax or, with
// past_half_pitch, an SDE would stretch by more than half a pitch; the message says which way to
// change the value: a rest length shorter than the route's is raised, a pretension lowered.
void check_strain_at_rest(const StrainAtRest& s, bool past_half_pitch = false);
// The run's first lines' warning when the strain passes kStrainWarn: the key and value, the
// strain, the tension and EA, what a belt takes and what to check; "" when it does not.
std::string strain_at_rest_warning(const StrainAtRest& s);  // Model::law_of holds a segment's number in a byte

}  // namespace beltsim
