// The scene's data: its definition (what a scenario script describes, in SI units, with the
// defaults of the parameter table, scene/parameter_default.hpp) and the Scene its build makes of
// it (build_scene, scene/scene.hpp): a Model and its initial static state.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/drive.hpp"
#include "model/model.hpp"
#include "scene/parameter_default.hpp"
#include "scene/route.hpp"

namespace beltsim {

// A spring-loaded tensioner arm carrying a pulley's centre (model.hpp's Arm, its law at the top of
// model/tensioner.cpp). The pulley's centre is where the arm holds it at t = 0, the installed
// angle. The static initial state balances the arm: with a preload (or the free angle angle0,
// which gives it) the belt's tension at rest is the one whose moment about the pivot the preload
// holds; with neither, the spring's free angle is the one that holds the belt's pretension.
struct TensionerDef {
  Vec2 pivot{0, 0};                // [m]
  double inertia = 0;              // [kg·m²] about the pivot, the pulley's mass included
  double stiffness = 0;            // [N·m/rad]
  std::optional<double> preload;   // [N·m] the spring's moment at the installed angle
  std::optional<double> angle0;    // [rad] the spring's free angle
  double damping = parameter_default("pulley.tensioner.damping");                  // [N·m·s/rad]
  double friction_torque = parameter_default("pulley.tensioner.friction_torque");  // [N·m]
  double friction_speed = parameter_default("pulley.tensioner.friction_speed");    // [rad/s]
  double asymmetric = parameter_default("pulley.tensioner.asymmetric");
  // its preload or free angle sets the belt's tension at rest (else the belt's pretension does)
  bool sets_tension() const { return preload || angle0; }
};

// A rotor behind a torsional spring-damper on a pulley (model.hpp's Coupling, its law at the top of
// model/coupling.cpp): an alternator's rotor behind a decoupler; with one_way the spring drives
// the rotor through an overrunning clutch, in the sense the pulley turns as the belt travels. The
// pulley's torque law acts on the rotor. At t = 0 the spring is relaxed and the rotor (and hub)
// turn with the pulley.
struct CouplingDef {
  double inertia = 0;    // [kg·m²] the rotor's
  double stiffness = 0;  // [N·m/rad]
  double damping = parameter_default("pulley.coupling.damping");  // [N·m·s/rad]
  bool one_way = false;
  double hub_inertia = parameter_default("pulley.coupling.hub_inertia");    // [kg·m²]
  double lock_damping = parameter_default("pulley.coupling.lock_damping");  // [N·m·s/rad]
  double drag_torque = parameter_default("pulley.coupling.drag_torque");    // [N·m]
};

struct PulleyDef {
  std::string name;
  Vec2 centre{0, 0};        // [m]
  double radius = parameter_default("pulley.radius");    // [m] pitch (contact) radius
  double inertia = parameter_default("pulley.inertia");  // [kg·m²]
  WrapSide wrap = WrapSide::inside;
  bool kinematic = false;   // speed prescribed by `speed` instead of driven by `torque`
  TimeSpeedLaw torque;      // [N·m]
  TimeSpeedLaw speed;       // [rad/s]
  std::optional<TensionerDef> tensioner;  // its centre on a tensioner arm
  std::optional<CouplingDef> coupling;    // a rotor behind a decoupler
};

// How the belt's stiffness and damping were given (docs/model.md, Parameter reading).
enum class StiffnessReading {
  rigidity,  // EA [N], EI [N·m²], axial damping per length [N·s]; per SDE: /l0, the rest length of an
             // element (bending damping as is, bending viscosity /l0)
  per_sde    // k [N/m], c [N·s/m], k_t [N·m/rad], c_t [N·m·s/rad] of each SDE as given
};

// Where an element sits on the belt at t = 0, for per-element properties such as μ.
struct ElementSite {
  int index = 0;                 // element number, 0..n-1 in the direction of travel
  Vec2 centre{0, 0};             // [m] its centre at t = 0
  double s = 0;                  // [m] arc length along the belt from where it leaves the first
                                 //     pulley of the route (element 0 sits at s = 0)
  double length = 0;             // [m] the belt's length along that path
  std::string pulley;            // the pulley it rides at t = 0, empty on a span
  std::map<std::string, double> meets, leaves;  // [m] s where the belt meets / leaves each pulley
};

// How the belt's tension at rest is given: exactly one of the three.
enum class Tensioning {
  pretension,   // the spans' tension at rest [N]; the rest length follows
  rest_length,  // the belt's stress-free length [m]; the tension follows
  strain        // the mounting strain, route length / rest length - 1; the tension follows
};

struct BeltDef {
  std::string preset;  // the belt preset whose values the scene took (scene/belt_presets.hpp), "" when none
  int elements = static_cast<int>(parameter_default("belt.elements"));
  Tensioning tensioning = Tensioning::pretension;
  double pretension = parameter_default("belt.pretension");  // [N]  (Tensioning::pretension)
  double rest_length = 0;           // [m]  (Tensioning::rest_length)
  double strain = 0;                // [-]  (Tensioning::strain)
  int loop_sense = -1;              // direction of travel round the loop: -1 clockwise, +1 anticlockwise
  std::vector<std::string> route;   // pulley names in travel order; empty: the order of definition
  StiffnessReading reading = StiffnessReading::rigidity;
  double EA = parameter_default("belt.EA");                        // [N]
  double EI = parameter_default("belt.EI");                        // [N·m²]
  double axial_damping = parameter_default("belt.axial_damping");  // [N·s] per unit length
  double bending_damping = parameter_default("belt.bending_damping");  // [N·m·s/rad] per SDE...
  std::optional<double> bending_viscosity;  // ...or per length [N·m²·s]: c_t = bending_viscosity / l0
  double k = 0, c = 0, kt = 0, ct = 0;  // per-SDE values for StiffnessReading::per_sde
  double e_tra = parameter_default("belt.e_tra"), e_tor = parameter_default("belt.e_tor");  // exponents
  double mass_per_length = parameter_default("belt.mass_per_length");  // [kg/m]
  double mu = parameter_default("belt.mu");  // friction coefficient of every element...
  std::vector<double> mu_per_element;  // ...unless given per element (size = elements)...
  std::function<double(const ElementSite&)> mu_at;  // ...or by where the element starts
  double rib_angle = parameter_default("belt.rib_angle");  // [°] the V-ribs' included angle β
  std::optional<double> mu_flank;  // the ribs' flank coefficient a scenario gave instead of mu (mu = mu_flank/sin(β/2))
};

// The contact law's constants per metre of belt along the pulley (the pitch), beside the paper's
// per-element constants in `Contact`: an element of pitch l gets c1 = c1_per_length·l, and so on,
// so the contact pressure does not change when the belt is divided finer.
struct ContactPerLength {
  std::optional<double> c1;  // [N/m³]
  std::optional<double> c2;  // [N/m²]
  std::optional<double> b;   // [N·s/m²]
};

// friction.segments: a stretch of belt [from, to] (m along the belt where each element starts, as
// belt.mu functions' site.s; wrapping round when from > to) with a friction law of its own; the
// law starts from the scene's friction table and takes the segment's keys
struct FrictionSegment {
  double from = 0, to = 0;  // [m]
  Friction law;
};

struct SceneDef {
  std::vector<PulleyDef> pulleys;
  BeltDef belt;
  Contact contact{parameter_default("contact.c1"), parameter_default("contact.c2"),
                  parameter_default("contact.damping"), parameter_default("contact.p_max")};  // per element
  ContactPerLength contact_per_length;  // ...unless given per length
  Friction friction{.dv = parameter_default("friction.dv"),
                    .law = FrictionKind::threlfall,
                    .static_ratio = parameter_default("friction.static_ratio"),
                    .stribeck_speed = parameter_default("friction.stribeck_speed"),
                    .exponent = parameter_default("friction.exponent"),
                    .viscous = parameter_default("friction.viscous"),
                    .bristle_stiffness = parameter_default("friction.bristle_stiffness"),
                    .bristle_damping = parameter_default("friction.bristle_damping"),
                    .release_time = parameter_default("friction.release_time")};
  std::vector<FrictionSegment> friction_segments;  // later segments override earlier ones
  double gravity = parameter_default("gravity");  // [m/s²]; 0 switches gravity off
  bool track_energy = false;
  bool allow_large = false;         // past the size limits that protect the machine (validate)
  std::vector<SprayZone> spray;     // spray zones (model/spray.hpp); `to` infinite: never stops
  // the parameters the scenario gave, as dotted keys ("belt.EA", "contact.c1", "pulley.driver.inertia"):
  // every other one takes its default, and the build lists those (Scene::inputs)
  std::set<std::string> given;
  // of those, the ones the belt's preset gave (belt.preset: scene/belt_presets.hpp), not the script
  std::set<std::string> from_preset;
};

// One input of a scene as the run reports it (parameters.csv, the run's first lines): its value
// after defaults, and whether the scenario gave it.
struct SceneInput {
  std::string name;   // dotted key, as in the scenario
  double value = 0;   // the value, unless `text` is set
  std::string text;   // a value that is a word ("cw", "per element")
  std::string unit;
  bool given = false; // false: a default was taken
  std::string note;   // where a default comes from (the paper, or ours) and what the value refers to
  // "" unless the value is derived from other inputs, then which ("belt.mu_flank = 0.3 and
  // belt.rib_angle = 40°": belt.mu); such an input is not the script's own (mark_derived)
  std::string derived;
  // the belt preset that gave the value ("6PK"), "" when the script gave it or a default was taken
  std::string preset;
};

struct Scene {
  Model model;
  Drive drive;                     // the initial drive: the pulleys' laws, μ per element
  Eigen::VectorXd y0;              // initial state (static equilibrium, at rest)
  Route route;                     // pitch-line route (radius r_p on every pulley)
  std::vector<std::string> route_names;
  std::vector<int> route_pulleys;  // pulley index of each route entry
  std::vector<double> penetration; // static penetration p0 of each pulley [m]
  StiffnessReading reading = StiffnessReading::rigidity;
  std::vector<SceneInput> inputs;  // every input, given or default (scene_inputs)
  double static_tension = 0;       // mean SDE force on the spans after the static solve [N]
  double static_residual = 0;      // max |acceleration| of the initial state [m/s²]
  bool static_retried = false;     // the static start needed its trust-region retry (scene.cpp)
  std::vector<ElementSite> sites; // where each element starts (as belt.mu functions see it)
  int find_pulley(const std::string& name) const;
  // per pulley: +1 when the belt goes round it anticlockwise, -1 clockwise (from the route)
  std::vector<int> senses() const;
  // the route span from pulley a to pulley b (either order), -1 when they are not neighbours
  int find_span(const std::string& a, const std::string& b) const;
  int element_nearest(const Vec2& point) const;
  // elements on route entry k's wrap: its pitch-line arc over the pitch
  double wrap_elements(size_t k) const { return route.arcs[k].length() / model.belt.pitch; }
};

// The SDE nearest the midpoint of route span sp in the state y (positions, then velocities), and
// its axial force [N]: the span's tension as the build, the runs and the outputs read it.
int span_sde(const Model& m, const Route::Span& sp, const double* y);
double span_force(const Model& m, const Route::Span& sp, const double* y);

// A scene build stopped by its stop flag (Ctrl-C, SIGTERM).
struct BuildInterrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What a scene build looks at, and tells, at every bisection step of its placement and every
// Newton iteration and line-search trial of its static solve (scene.hpp, build_scene): a belt of
// thousands of elements takes seconds to minutes there (19 000 elements: 20-30 s on the project's
// machine).
struct BuildWatch {
  const std::atomic<bool>* stop = nullptr;  // set (Ctrl-C, SIGTERM): the build ends with BuildInterrupted
  // told at each of those polls, with the fields below (script/progress.hpp draws them once the
  // build has taken a second); none: nothing told
  std::function<void(const BuildWatch&)> progress;
  int elements = 0;        // the belt's
  const char* stage = "";  // "placing the belt", "static state"
  int newton = 0;          // Newton iterations of the static solve so far, every pass and retry
  double residual = -1;    // [m/s²] its largest acceleration after the last of them (-1: none yet)
};

}  // namespace beltsim
