// The scene's parameters: one table of every key a scenario's tables take (scene, belt, belt.sde,
// contact, friction, pulley, pulley.tensioner, pulley.coupling, spray), with its unit, its default
// and whose that default is, its rule and where its value lives in a SceneDef. The Lua readers
// (script/lua_scene_parts.cpp), the validation (validate(SceneDef)), the scene's inputs in
// parameters.csv and the run's first lines (scene_inputs), the checkpoint's inputs (scene_io.cpp)
// and the parameter tables of docs/lua-api.md (parameters_markdown) all come from it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "scene/parameter_default.hpp"

namespace beltsim {

struct SceneDef;
struct PulleyDef;

// whose a default is
enum class Whose {
  none,     // no default: required, or an alternative to another key
  paper,    // the paper's value
  reading,  // the paper's value, read as docs/model.md (Parameter reading) says
  ours      // not in the paper: our choice
};

// how a scenario gives the value
enum class Kind {
  number,   // a number, read by the table's reader
  integer,  // a whole number, read by the table's reader
  other     // a word, a list, a law or a table: read by its own code (script/lua_scene_parts.cpp)
};

// the range a number must lie in; every rule also requires a finite number
enum class Rule {
  none,
  finite,
  positive,
  non_negative,
  exponent,
  at_least_three,
  friction_coefficient,
  slip_band,
  pulley_radius,
  strain
};

// The largest friction coefficient accepted (Rule::friction_coefficient): a poly-V rib's effective
// coefficient μ/sin(β/2) stays below 5 (rubber on steel, μ up to 1.5, over sin 20°); a larger one
// changes no answer but shrinks the steps, the friction band's stiffness μ·N/Δv growing with it.
constexpr double kMuMax = 10;

// [m/s] The widest friction band accepted (Rule::slip_band, friction.dv). Within |v_T| < Δv the
// regularised laws give μ_i·v_T/Δv: an element reaches its kinetic μ only at a slip of Δv, and a
// belt carrying a load creeps at up to Δv on every pulley (docs/friction.md). Belts run at a few m/s
// and up (the paper's drive 7 m/s, cars' 10-50 m/s) and creep at about 1 % of that, so a band of
// 1 m/s already lets the drive slip tenfold more than a belt does; a band as wide as the belt's
// speed (dv = 1e300 ran so) transmits next to nothing: no friction in effect. The paper's is
// 1e-5 m/s, the known answers' widest 0.05 m/s.
constexpr double kDvMax = 1;

// [m] The largest pulley radius accepted (Rule::pulley_radius). Lengths are in metres; a scenario
// written in millimetres (radius = 100 for 0.1 m) would otherwise be refused later for a reason
// that sends its writer the wrong way (the pulleys' inertias below 1 % of the belt's on the wrap).
// Belt pulleys stay well below it: a car's 0.03-0.1 m, an industrial drive's up to about 1 m, a
// conveyor's drum about 1 m.
constexpr double kRadiusMax = 5;

// [-] The belt's strain at rest (route pitch length / rest length - 1) above which the run's first
// lines warn (strain_at_rest_warning, scene/validate.hpp), however the tension at rest is given. A
// PK belt is mounted at a few tenths of a per cent: the paper's 500 N on its EA of 1.52e5 N is
// 0.33 %, docs/automotive.md's 6PK at 280 N (EA = 1.824e5 N) 0.15 %; under load its tight span
// stays well under 1-2 % (docs/belts.md measures 722 N on the paper's belt in the automotive
// drive: 0.47 %). An elastic flat or round belt (polyurethane) is mounted at some 3 to 8 %
// (scripts/light_belt.lua's datasheet belt at 5 %). Past 10 % a value is more likely a slip (a
// percentage written as a strain, a pretension in other units, another belt's rest length) than
// a belt.
constexpr double kStrainWarn = 0.1;

// [-] The strain at rest refused (Rule::strain for belt.strain; a rest length or a pretension that
// gives it, check_strain_at_rest): the belt stretched by half its length. Its tension cords
// (polyester, nylon, aramid, glass, steel) break at a few per cent to some 25 %, and the axial
// spring EA/l0 is a belt's only at small strains; 0.5 to 1 is where a percentage written as a
// strain lands (0.9 for 0.9 %). (The model's own limit is an SDE stretched by half a pitch: a
// strain of 1 for a rest length or strain, T = EA/2 for a pretension.)
constexpr double kStrainMax = 0.5;

// [°] The V-ribs' included angle a scene may give without a warning (belt.rib_angle): a PK belt's
// is 40° (ISO 9982), a classical V-belt's about as much (its pulleys' grooves 32° to 38°); the
// angle sets the effective μ = mu_flank/sin(β/2), which at 20° is already 5.8 times the flank's.
// An angle given in radians (a PK belt's 40° is 0.698 rad; every V-rib's angle is below
// kRadiansBelow in radians) is told so.
constexpr double kRibAngleMin = 20, kRibAngleMax = 60, kRadiansBelow = 3;

// [kg/m³, m] The pulley inertia above which the run's first lines warn (belt pulley inertia
// against its radius): that of a solid steel disc of the pulley's radius kSolidWidth wide, ½·ρ·π·w·r⁴.
// A belt pulley is a rim on a hub, 20-50 mm wide: the paper's default inertia is a steel disc of
// 0.1 m, 20 mm wide; the example scripts' stay below a disc 0.1 m wide. A rotor lumped into the
// pulley (an alternator's, behind its 28 mm pulley: some 2e-3 kg·m², a disc 0.3 m wide; an
// engine's crank and flywheel) may come near it; an inertia in g·cm² (1e-7 kg·m²) or kg·cm²
// (1e-4 kg·m²) written as kg·m² passes it by orders of magnitude.
constexpr double kSteelDensity = 7850, kSolidWidth = 1;

// where a parameter's value lives in a SceneDef (a pulley's in its PulleyDef)
using Slot = std::variant<std::monostate, double*, int*, std::optional<double>*>;

struct Parameter {
  std::string_view table;  // the scenario's table: "scene", "belt", "belt.sde", "contact", "friction", "pulley",
                           // "pulley.tensioner", "pulley.coupling", "spray" (a spray zone's: its
                           // numbers have no slot, script/lua_scene_parts.cpp reads them and validate
                           // checks them by their rules)
  std::string_view key;    // the key in that table
  Kind kind;
  std::string_view unit;           // SI; "" when dimensionless or not a number
  std::optional<double> fallback;  // the default of a number
  std::string_view fallback_text;  // the default of anything else, as the docs show it ("" when none)
  Whose whose;
  Rule rule;
  std::string_view note;                // what it is and what it refers to
  Slot (*slot)(SceneDef&, PulleyDef&);  // nullptr: no single number (read and checked by their own code)
  bool (*applies)(const SceneDef&);     // nullptr: always; else whether the scene uses it
  std::string (*word)(const SceneDef&, const PulleyDef&);  // a value that is a word, "" when it is a number

  // "belt.mass_per_length", "pulley.radius", "gravity" (a key of the scene table stands alone)
  std::string dotted() const;
};

// every parameter, in the order the docs, the valid-key lists and parameters.csv give them
std::span<const Parameter> parameters();
// the parameters of one table ("belt", "pulley", ...), in order
std::vector<const Parameter*> parameters_of(std::string_view table);
// the keys of one table, as a valid-key list
std::vector<std::string> keys_of(std::string_view table);
// the parameter of a dotted key ("contact.damping", "pulley.inertia"); nullptr when none
const Parameter* find_parameter(std::string_view dotted);
// the default of a number parameter: parameter_default (scene/parameter_default.hpp)

// the value a parameter has in d (p: the pulley's), nullopt when it has no number there (an
// optional not given, a parameter read by its own code)
std::optional<double> value_of(const Parameter& par, const SceneDef& d, const PulleyDef* p = nullptr);

// "the paper's", "our reading of the paper's", "ours", ""
std::string_view whose_text(Whose w);
// the rule's words: "must be > 0"
std::string_view rule_text(Rule r);

// The parameter tables of docs/lua-api.md: one Markdown table per scenario table (key, unit,
// default, meaning), as `beltsim help parameters` prints them and the docs hold them.
std::string parameters_markdown();

}  // namespace beltsim
