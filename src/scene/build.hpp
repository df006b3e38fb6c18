// The stages of build_scene (scene.cpp), in the order it runs them. Each fills one part of the
// Scene from the definition and what the stages before it made, and throws ParameterError (with
// the key, the reason and the value) when that part cannot be built.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/contacts.hpp"
#include "model/model.hpp"
#include "scene/route.hpp"
#include "scene/scene_types.hpp"

namespace beltsim::build {

// 1. the model's pulleys, in definition order
std::vector<Pulley> make_pulleys(const SceneDef& d);
// the initial drive: each pulley's torque or speed law (μ is filled by element_mu)
Drive make_drive(const SceneDef& d);

// 2. the route's order (belt.route, or the order of definition): each entry's name, pulley index
// and pitch circle, wrapped in the loop's sense (inside the loop) or against it (on the back)
struct RouteOrder {
  std::vector<std::string> names;
  std::vector<int> pulleys;
  std::vector<RouteCircle> circles;
};
RouteOrder route_order(const SceneDef& d, const std::vector<Pulley>& pulleys);
// throws when a wrap of `route` holds fewer than 3 elements of the pitch route.length / elements
void check_wraps(const Route& route, const std::vector<std::string>& names, int elements);
// throws when a speed law prescribes more than kPulleySpeedMax once its ramps and tables have ended
// (peak_speed: a Lua function's is not known), where every run would stop
void check_speeds(const std::vector<Pulley>& pulleys, const Drive& dr);
// throws when a free pulley's inertia is below kWrapInertiaMin of the belt's on its wrap
// (mass_per_length · wrap length · r²): the step-size control cannot follow so light a pulley
constexpr double kWrapInertiaMin = 0.01;
void check_inertias(const Route& route, const RouteOrder& order, const std::vector<Pulley>& pulleys, const Drive& dr,
                    double mass_per_length);

// 3. the per-SDE values of an element of rest length l0 (docs/model.md, Parameter reading), into rigid_length, mass,
// rot_inertia, k, kt, c and ct: the rigidities refer to l0 (k = EA/l0, k_t = EI/l0,
// c = axial_damping/l0, c_t = bending_viscosity/l0 or bending_damping per SDE), per-SDE values are
// taken as given; the mass is ρ·l0, ρ per metre of unstretched belt
void set_rest_length(Belt& b, const BeltDef& bd, double l0);
// throws when a per-SDE value is beyond what double precision integrates (> 1e15 or not finite)
void check_sde_values(const Belt& b, const BeltDef& bd);

// 4. the tension at rest: given (pretension), or estimated from the rest length on straight spans
// (T = k·(l - l0)^e) when the rest length or strain is given
struct TensionAtRest {
  const char* key;  // how it was given, for the messages: "belt.pretension", ...
  double value;     // the value given
  double rest = 0;     // [m] the rest length of an element when the rest length or strain is given, else 0
  double tension = 0;  // [N] the tension at rest
};
// sets b's rest length when the rest length is given (set_rest_length); throws when the belt would
// hang slack or each SDE would stretch by more than half a pitch
TensionAtRest tension_at_rest(const BeltDef& bd, double route_length, Belt& b);
// throws when the belt's weight over its longest span passes its tension at rest t (it would sag),
// naming what is at fault: gravity when the tension would hold the belt under Earth's, else what
// gave the tension (t.key, or the tensioner of d that sets it) with its value and unit
void check_sag(const Route& route, const SceneDef& d, const TensionAtRest& t);

// 5. the contact constants of an element of the given pitch (the per-length ones times the pitch)
Contact element_contact(const SceneDef& d, double pitch);
// the static penetration p0 of a belt of the given tension on a circle of the given radius:
// c1·p0² + c2·p0 = N0 = 2·T·sin(α/2), α the angle one pitch subtends at radius - p0
double static_penetration(const Contact& c, double pitch, double radius, double tension);
// static_penetration on each circle of the route (route order); throws when one is not finite or
// deeper than half the radius (the messages quote the contact constants of `d`)
std::vector<double> penetrations(const RouteOrder& order, const Contact& c, double pitch, double tension,
                                 const SceneDef& d);
// the path of the element centres: the route with each circle shrunk by its penetration
Route centre_path(const RouteOrder& order, const std::vector<double>& penetration, int loop_sense);

// 6. closing the loop. walk places n element centres along `path` from s = 0, rods of half-length
// h along the path's tangent, each SDE's gap `gap`; returns where element n would go (=
// path.length when the loop closes) and, when s is given, each element's arc length
double walk(const Route& path, int n, double h, double gap, std::vector<double>* s);
// the SDE gap that closes the loop with n elements (bisection): with the pretension given, the
// rest length whose gaps carry it (set into b, the gap following it through k = EA/l0); with the
// rest length given, the gap. Throws when a given rest length leaves the belt slack on the path.
// Polls `watch` (scene_types.hpp) at every bisection step, as static_solve at every Newton
// iteration and line-search trial (counted in watch.newton, the residual in watch.residual).
double close_loop(const Route& path, int n, const BeltDef& bd, const TensionAtRest& t, Belt& b, BuildWatch& watch);

// 7. the state at the placement: the elements at rest at arc lengths s along path, each rod along
// the tangent (angles continuous along the belt), the pulleys at rest
Eigen::VectorXd place(const Model& m, const Route& path, const std::vector<double>& s);

// 8. where each element starts (index, centre, s, the pulley it rides, where the belt meets and
// leaves each pulley), from the centre path, its route names, the placed state and arc lengths
std::vector<ElementSite> element_sites(const Route& path, const std::vector<std::string>& names,
                                       const Eigen::VectorXd& y0, const std::vector<double>& s);
// μ of each element: belt.mu, mu_per_element or mu_at(site) (checked >= 0)
std::vector<double> element_mu(const BeltDef& bd, const std::vector<ElementSite>& sites);
// the segments' friction laws (Model::laws) and each element's (Model::law_of) from where the
// elements start along the belt, s
void set_segment_laws(Model& m, const SceneDef& d, const std::vector<double>& s);

// the kinematic pulleys' speeds in y: their prescribed speed at t = 0 (after a step at 0); after
// element_mu, so that Lua laws are called in the order the scene lists them
void set_start_speeds(const Model& m, const Drive& dr, Eigen::VectorXd& y);

// 9. the static state. static_solve: Newton iterations with a damped step on the elements' static
// equations of m (pulleys held), from y; returns the final max |acceleration| [m/s²]. max_move > 0
// limits how far one step moves any element centre (a trust region).
double static_solve(const Model& m, const Drive& dr, Eigen::VectorXd& y, double max_move, BuildWatch& watch);
// the mean SDE force on the spans of sc.route in the state y [N]
double span_tension(const Model& m, const Route& route, const Eigen::VectorXd& y);
// from the placement in sc.y0 and sc.model.belt: static_solve with every pulley held, the rest
// length corrected until the spans carry the pretension (rest_given: left as it is); fills y0,
// the belt, static_residual and static_tension; when the plain iteration does not
// converge or leaves a pulley, repeats it with a trust region of a tenth of a pitch per step
// (static_retried). Returns the name of a route pulley the belt left untouched, empty when none.
std::string settle(Scene& sc, const BeltDef& bd, bool rest_given, BuildWatch& watch);

// [m/s²] The largest acceleration a static state is left with (settle), against 1e5..1e9 in the
// raw placement.
constexpr double kStaticConverged = 1.0;

// 10. throws when the static state, rest length, tension or residual is not finite
void check_finite(const Scene& sc, const SceneDef& d, double tension);

// How much stiffer than the belt's SDE (its axial stiffness at the tension at rest) an element's
// contact (dN/dp = c2 + 2·c1·p0 at the static penetration) may be before a failed static solve
// is laid to it. The Newton iteration starts from a placement that is off where a span meets a
// wrap; the contact's force on that error, and the steps that undo it, grow with its stiffness
// against the belt's, until the iteration wanders along the belt's free sliding mode and stalls
// or leaves a pulley. On the paper's drive (60 elements, 500 N, gravity on) the paper's contact is
// 0.16 times as stiff as the SDE; c2 at 3.4 times converged, 4.3 times (120 elements) and 8.5
// times (60) did not, c2 = 1e14 N/m (1.3e7 times) lost the driver (each a few elements more or
// fewer alike), and from c2 = 1e14 the rounding of a position (1e-17 m) alone is a force past the
// residual test.
constexpr double kStiffContact = 1;
// 11. throws when the static solve failed: a route pulley left untouched (`lost`), or (with the
// contact more than kStiffContact times as stiff as the belt) a residual past kStaticConverged,
// naming the contact constant that makes it so stiff, with its value and the paper's; else,
// with a pulley lost, belt.elements. An unconverged state of a softer contact is kept (its
// residual is in scene:info(); the run's first lines warn of it: static_state_warning).
void check_static_state(const Scene& sc, const SceneDef& d, const std::string& lost, double tension);

// Tensioner arms (scene/tensioner.cpp). validate_tensioner: throws on what the parameter table's
// rules (validate) do not cover: the pivot, the arm's length, a prescribed speed; make_arms: the
// model's arms from the pulleys' tensioner definitions, each at its installed angle (after
// make_pulleys); set_arm_angles: those angles into
// the state y (before the static solve, which holds them); balance_arms: each spring's free angle
// and pressing sense from the belt's moment about its pivot in the static state sc.y0.
void validate_tensioner(const PulleyDef& p);
void make_arms(const SceneDef& d, Model& m);
void set_arm_angles(const Model& m, Eigen::VectorXd& y);
void balance_arms(Scene& sc);
// the preload that sets the belt's tension at rest (the one arm that gives preload or angle0),
// none when no arm does; throws when two arms do or the belt's tension is given as well
std::optional<double> tensioner_preload(const SceneDef& d);
// refuses a tensioner's angle0 on the side of the installed angle where the spring would turn the
// arm the way the belt does (off the belt: no tension at rest holds it), naming the angle on the
// other side that gives the same preload; sc is a build of d, pulley the tensioner's
void check_angle0_side(const Scene& sc, const SceneDef& d, int pulley);
// the belt's moment about arm a's pivot in the static state sc.y0 [N·m], from its contact records
// at t = 0 (model/contacts.hpp: fill_contacts)
double arm_belt_moment(const Scene& sc, const ContactRecords& contacts, int a);

// Coupled rotors (scene/coupling.cpp). validate_coupling: throws on a bad parameter;
// make_couplings: the model's couplings from the pulleys' coupling definitions (after
// make_pulleys, make_arms); start_couplings: each rotor (and hub) at its pulley's angle and speed
// in y (after the pulleys' start speeds).
void validate_coupling(const PulleyDef& p);
void make_couplings(const SceneDef& d, Model& m);
void start_couplings(const Model& m, Eigen::VectorXd& y);

}  // namespace beltsim::build
