// The scene's build: a definition (scene/scene_types.hpp) checked (scene/validate.hpp) and turned
// into a Model and its initial static state (build_scene, by the stages of scene/build.hpp); the
// warnings of the run's first lines about it; its inputs as parameters.csv lists them.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "scene/parameters.hpp"
#include "scene/scene_types.hpp"
#include "scene/validate.hpp"

namespace beltsim {

// Below this many elements on a wrap, the wrap's contact and slip arcs and the span tensions
// next to it are resolved by a handful of elements: the run's first lines warn (coarse_wraps).
inline constexpr double kWrapElementsWarn = 10;

// One line naming every pulley whose wrap holds fewer than kWrapElementsWarn elements (each with
// its count and wrap), what so coarse a wrap costs and the belt.elements that would put
// kWrapElementsWarn on the coarsest. Empty when no wrap is so coarse.
std::vector<std::string> coarse_wraps(const Scene& sc);

// One line per free pulley whose torque's per_speed_table lies wholly on the other side of zero
// from the speeds the pulley turns at (its sense at the drive's steady speeds, bending_loss.hpp's
// steady_belt_speed, else as belt.direction says): the table then gives one torque throughout.
std::vector<std::string> wrong_side_maps(const Scene& sc);

// The axial dampers' force from their gap vectors' turning round the tightest wrap at the drive's
// steady speeds, past kGapRotationWarn of the gaps' spring force (a damping far above a belt's:
// a user's 1e4 times the paper's carried 9 kN spans on a 500 N drive); "" below it, or when the
// steady speed is not known.
inline constexpr double kGapRotationWarn = 0.1;
std::string gap_rotation_warning(const Scene& sc);

// The static initial state not found (its residual past kStaticConverged), or found at a tension
// more than 0.1 % from the belt.pretension asked; "" when neither.
std::string static_state_warning(const Scene& sc);

// One line per free pulley of a drive that a prescribed speed drives whose torque, a law of time
// alone that settles (a constant, steps, ramps, a table), turns it once settled the way it runs at
// the drive's steady speeds: a load given with the sign of a driver (a user's alternator at -3 N·m
// turning clockwise was pushed by its "load"). None where no pulley's speed is prescribed.
std::vector<std::string> aiding_loads(const Scene& sc);

// The belt's strain at rest past kStrainWarn (scene/parameters.hpp), with how its tension at rest
// was given (strain_at_rest_warning, scene/validate.hpp); "" when it is a belt's.
std::string strain_warning(const Scene& sc);

// [m/s] Above this belt speed the run's first lines warn (belt_speed_warning): makers rate PK
// (poly-V) belts for belt speeds up to about 50-60 m/s, so past 60 m/s no PK belt is rated, and
// the belt's centrifugal tension m'·v² (346 N at 60 m/s on the paper's belt of 0.096 kg/m) is of
// the order of its tension at rest (docs/model.md, limits the scene build enforces).
inline constexpr double kBeltSpeedWarn = 60;

// The fastest belt speed the drive's speeds give before it runs, when it passes kBeltSpeedWarn:
// each kinematic pulley's prescribed speed at the start (the initial state's) and once its ramps
// and tables have ended, its sines and harmonics at their peaks (bending_loss.hpp steady_value),
// times its pitch radius; with no kinematic pulley, the steady belt speed the free pulleys' torques
// balance at (steady_belt_speed), on the pulley it turns fastest. One line naming the pulley, its
// speed [rad/s], the belt speed [m/s], the threshold and the centrifugal tension against the
// tension at rest; "" when no speed passes it (or none is known: a law given as Lua code is read
// at the start only).
std::string belt_speed_warning(const Scene& sc);
// A speed law's largest speed once its ramps and tables have ended [rad/s], signed: its steady
// value plus its sines' and harmonics' amplitudes; nullopt for a law given as Lua code.
std::optional<double> peak_speed(const TimeSpeedLaw& speed);
// belt_speed_warning's line for pulley `pulley` turning at omega [rad/s] `when` (prescribed: its
// speed given, else reached); "" when the belt speed |omega|·r does not pass kBeltSpeedWarn.
std::string belt_speed_text(const Scene& sc, int pulley, double omega, const std::string& when, bool prescribed);

// The belt's sag under its weight past kSagWarn of its longest span at the tension its input gives
// (δ/L = ρ·g·L/8T; check_sag refuses one that would hang, T < ρ·g·L), naming that input (a
// pretension below 10 N: "in N"); "" when smaller. The static start holds the spans straight.
inline constexpr double kSagWarn = 0.01;
std::string sag_warning(const Scene& sc);

// Each spray zone whose circle does not reach the belt's path at rest (the polygon of its elements'
// centres): its number, circle and distance; it wets nothing unless the belt moves there.
std::vector<std::string> spray_warnings(const Scene& sc);

// Values given in another unit than their key's, likely: a belt.rib_angle no V-rib has
// (rib_angle_problem, scene/validate.hpp: in radians when below kRadiansBelow), a pulley inertia
// above a solid steel disc of its radius kSolidWidth wide (in g·cm² or kg·cm²?)
// (scene/parameters.hpp). Given values only; empty when none.
std::vector<std::string> unit_warnings(const Scene& sc);

// What the run's first lines warn of (scene:info().warnings lists the same): the values in another
// unit, likely (unit_warnings), a strain at rest past a belt's (strain_warning), a belt speed past a
// PK belt's rating (belt_speed_warning), spans that sag (sag_warning), spray zones off the belt
// (spray_warnings), the coarse wraps,
// the speed maps on the wrong side of zero (wrong_side_maps), each free pulley whose torque grows
// with its speed (per_speed > 0, an energy source: the speed grows as exp(per_speed·t/J) unless
// the belt holds it back), and bending dampers that will take more than a few per cent of the
// power the drive transmits (scene/bending_loss.hpp).
std::vector<std::string> scene_warnings(const Scene& sc);

// Validates every parameter (ParameterError with the reason and the value) and builds the scene.
// The placement and the static solve poll *stop (when given) at every bisection step, Newton
// iteration and line-search trial and throw BuildInterrupted when it is set: a long build
// (thousands of elements) ends within a fraction of a second.
Scene build_scene(const SceneDef& def, const std::atomic<bool>* stop = nullptr);
// The same, watched (scene_types.hpp, BuildWatch): its stop flag polled and its progress told there.
Scene build_scene(const SceneDef& def, BuildWatch& watch);

// The scene's inputs after defaults, in the order parameters.csv lists them.
std::vector<SceneInput> scene_inputs(const SceneDef& def);
// One input of parameter `par` under `name` ("pulley.driver.inertia"): a number `value`, or a
// word `text`; its unit and note from the table.
SceneInput scene_input(const Parameter& par, const std::string& name, double value, const std::string& text,
                       bool given);
// The inputs derived from others: belt.mu from belt.mu_flank and belt.rib_angle (the rib wedge's
// effective μ) gets SceneInput::derived and a note naming them (a scene's inputs, a checkpoint's)
void mark_derived(std::vector<SceneInput>& inputs);

}  // namespace beltsim
