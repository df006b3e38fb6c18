#include "scene/parameters.hpp"

#include <algorithm>
#include <stdexcept>

#include "scene/scene_types.hpp"

namespace beltsim {

namespace {

using K = Kind;
using W = Whose;
using R = Rule;

bool rigidity(const SceneDef& d) { return d.belt.reading == StiffnessReading::rigidity; }
bool per_sde(const SceneDef& d) { return d.belt.reading == StiffnessReading::per_sde; }
bool stribeck(const SceneDef& d) { return d.friction.law != FrictionKind::threlfall; }  // LuGre's curve too
bool lugre(const SceneDef& d) { return d.friction.law == FrictionKind::lugre; }

// The table. A number's default is `fallback`; what a scenario may leave out but has no single
// number (a law, a route) says its default in `fallback_text`.
// clang-format off
constexpr Parameter kParameters[] = {
    // ---- beltsim.scene{...} ----
    {"scene", "pulleys", K::other, "", {}, "", W::none, R::none,
     "list of pulley tables (below), at least two; required", nullptr, nullptr, nullptr},
    {"scene", "belt", K::other, "", {}, "the belt table's defaults", W::none, R::none, "belt table (below)", nullptr,
     nullptr, nullptr},
    {"scene", "contact", K::other, "", {}, "the contact table's defaults", W::none, R::none,
     "contact law, eq. 2 (table below)", nullptr, nullptr, nullptr},
    {"scene", "friction", K::other, "", {}, "the friction table's defaults", W::none, R::none,
     "friction law, eqs. 3-4 (table below)", nullptr, nullptr, nullptr},
    {"scene", "gravity", K::number, "m/s²", 9.81, "", W::ours, R::finite, "gravity along -y; 0 switches it off",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.gravity; }, nullptr, nullptr},
    {"scene", "energy", K::other, "", {}, "`false`", W::none, R::none,
     "track work and dissipation per channel (adds energy.* columns)", nullptr, nullptr, nullptr},
    {"scene", "spray", K::other, "", {}, "none", W::none, R::none,
     "spray zones: a list of tables (below) that wet the belt where it passes", nullptr, nullptr, nullptr},
    {"scene", "allow_large", K::other, "", {}, "`false`", W::none, R::none,
     "past the limit of 20 000 elements (hours per simulated second)", nullptr, nullptr, nullptr},

    // ---- pulleys = { {...}, ... } ----
    {"pulley", "name", K::other, "", {}, "", W::none, R::none, "used in column names and routes; required, one per pulley, no control characters", nullptr,
     nullptr, nullptr},
    {"pulley", "centre", K::other, "m", {}, "", W::none, R::none, "{x, y} of its axis; required", nullptr, nullptr,
     nullptr},
    {"pulley", "center", K::other, "m", {}, "", W::none, R::none, "the same as centre (one of the two)", nullptr,
     nullptr, nullptr},
    {"pulley", "radius", K::number, "m", 0.1, "", W::paper, R::pulley_radius, "contact (pitch) radius r_p",
     [](SceneDef&, PulleyDef& p) -> Slot { return &p.radius; }, nullptr, nullptr},
    {"pulley", "inertia", K::number, "kg·m²", 0.025, "", W::ours, R::positive,
     "moment of inertia about its axis (the default is a steel disc of r = 0.1 m, 20 mm wide); above a solid "
     "steel disc of its radius 1 m wide the run's first lines warn (in g·cm² or kg·cm²?)",
     [](SceneDef&, PulleyDef& p) -> Slot { return &p.inertia; }, nullptr, nullptr},
    {"pulley", "wrap", K::other, "", {}, "`\"inside\"`", W::ours, R::none,
     "\"inside\" the loop, or \"back\" (the belt's back side, e.g. a tensioner idler)", nullptr, nullptr,
     [](const SceneDef&, const PulleyDef& p) -> std::string { return p.wrap == WrapSide::inside ? "inside" : "back"; }},
    {"pulley", "torque", K::other, "N·m", {}, "none", W::none, R::none, "applied torque law (Laws, below)", nullptr,
     nullptr, nullptr},
    {"pulley", "speed", K::other, "rad/s", {}, "", W::none, R::none,
     "prescribed speed law: the pulley becomes kinematic (Laws, below)", nullptr, nullptr, nullptr},
    {"pulley", "tensioner", K::other, "", {}, "none: a fixed centre", W::none, R::none,
     "its centre on a spring-loaded arm (table below)", nullptr, nullptr, nullptr},
    {"pulley", "coupling", K::other, "", {}, "none: one body", W::none, R::none,
     "a rotor behind a torsional spring-damper, optionally one-way (table below); the torque law then acts on "
     "the rotor", nullptr, nullptr, nullptr},

    // ---- a pulley's tensioner = {...}: its centre on a spring-loaded arm ----
    {"pulley.tensioner", "pivot", K::other, "m", {}, "", W::none, R::none, "{x, y} of the arm's pivot; required",
     nullptr, nullptr, nullptr},
    {"pulley.tensioner", "inertia", K::number, "kg·m²", {}, "", W::none, R::positive,
     "the arm's moment of inertia about the pivot, the pulley's mass included; required",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->inertia) : Slot(); }, nullptr,
     nullptr},
    {"pulley.tensioner", "stiffness", K::number, "N·m/rad", {}, "", W::none, R::positive,
     "the spring's stiffness k; required",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->stiffness) : Slot(); }, nullptr,
     nullptr},
    {"pulley.tensioner", "preload", K::number, "N·m", {}, "", W::none, R::positive,
     "the spring's moment at the installed angle; sets the belt's tension at rest",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->preload) : Slot(); }, nullptr,
     nullptr},
    {"pulley.tensioner", "angle0", K::number, "rad", {}, "", W::none, R::finite,
     "the spring's free angle, instead of preload; sets the belt's tension at rest; within a turn of the installed "
     "angle, on the side from which the spring presses the pulley on the belt (else refused)",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->angle0) : Slot(); }, nullptr,
     nullptr},
    {"pulley.tensioner", "damping", K::number, "N·m·s/rad", 0, "", W::ours, R::non_negative,
     "the arm's viscous damping c",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->damping) : Slot(); }, nullptr,
     nullptr},
    {"pulley.tensioner", "friction_torque", K::number, "N·m", 0, "", W::ours, R::non_negative,
     "the pivot's friction torque T_f (T_f·tanh(ψ̇/friction_speed))",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->friction_torque) : Slot(); },
     nullptr, nullptr},
    {"pulley.tensioner", "friction_speed", K::number, "rad/s", 0.01, "", W::ours, R::positive,
     "the width of the friction torque's tanh",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->friction_speed) : Slot(); },
     nullptr, nullptr},
    {"pulley.tensioner", "asymmetric", K::number, "", 1, "", W::ours, R::positive,
     "damping and friction times this while the belt pushes the arm back (1: symmetric)",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.tensioner ? Slot(&p.tensioner->asymmetric) : Slot(); }, nullptr,
     nullptr},

    // ---- a pulley's coupling = {...}: a rotor behind a decoupler ----
    {"pulley.coupling", "inertia", K::number, "kg·m²", {}, "", W::none, R::positive,
     "the rotor's moment of inertia J_r (an alternator's rotor); required",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.coupling ? Slot(&p.coupling->inertia) : Slot(); }, nullptr,
     nullptr},
    {"pulley.coupling", "stiffness", K::number, "N·m/rad", {}, "", W::none, R::positive,
     "the decoupler spring's torsional stiffness k; required",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.coupling ? Slot(&p.coupling->stiffness) : Slot(); }, nullptr,
     nullptr},
    {"pulley.coupling", "damping", K::number, "N·m·s/rad", 0, "", W::ours, R::non_negative,
     "the decoupler's viscous damping c",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.coupling ? Slot(&p.coupling->damping) : Slot(); }, nullptr,
     nullptr},
    {"pulley.coupling", "one_way", K::other, "", {}, "`false`", W::ours, R::none,
     "`true`: an overrunning clutch behind the spring drives the rotor only in the sense the pulley turns as the "
     "belt travels",
     nullptr, nullptr,
     [](const SceneDef&, const PulleyDef& p) -> std::string {
       return p.coupling ? (p.coupling->one_way ? "true" : "false") : "";
     }},
    {"pulley.coupling", "hub_inertia", K::number, "kg·m²", 1e-4, "", W::ours, R::positive,
     "one way: the clutch hub's inertia J_h (with the spring's end)",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.coupling ? Slot(&p.coupling->hub_inertia) : Slot(); }, nullptr,
     nullptr},
    {"pulley.coupling", "lock_damping", K::number, "N·m·s/rad", 200, "", W::ours, R::positive,
     "one way: the engaged clutch's viscous lock c_L (it slips torque/c_L)",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.coupling ? Slot(&p.coupling->lock_damping) : Slot(); }, nullptr,
     nullptr},
    {"pulley.coupling", "drag_torque", K::number, "N·m", 0.05, "", W::ours, R::positive,
     "one way: the clutch's drag on the rotor while it overruns",
     [](SceneDef&, PulleyDef& p) -> Slot { return p.coupling ? Slot(&p.coupling->drag_torque) : Slot(); }, nullptr,
     nullptr},

    // ---- belt = {...} ----
    {"belt", "preset", K::other, "", {}, "none", W::none, R::none,
     "a PK section's values, \"3PK\" … \"8PK\" (the presets' table below, docs/belts.md), for the keys the "
     "belt table does not give itself",
     nullptr, nullptr, [](const SceneDef& d, const PulleyDef&) -> std::string { return d.belt.preset; }},
    {"belt", "elements", K::integer, "", 60, "", W::paper, R::at_least_three, "number of elements",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.elements; }, nullptr, nullptr},
    {"belt", "pretension", K::number, "N", 500, "", W::paper, R::positive,
     "tension the spans carry at rest; the rest length follows",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.pretension; },
     // not an input when a tensioner's preload or angle0 sets the tension (the build finds it)
     [](const SceneDef& d) {
       return d.belt.tensioning == Tensioning::pretension &&
              std::none_of(d.pulleys.begin(), d.pulleys.end(), [](const PulleyDef& p) {
                return p.tensioner && p.tensioner->sets_tension();
              });
     },
     nullptr},
    {"belt", "rest_length", K::number, "m", {}, "", W::none, R::positive,
     "the belt's stress-free length (a datasheet's), instead of pretension",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.rest_length; },
     [](const SceneDef& d) { return d.belt.tensioning == Tensioning::rest_length; }, nullptr},
    {"belt", "strain", K::number, "", {}, "", W::none, R::strain,
     "mounting strain (route pitch length / rest length - 1), instead of pretension",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.strain; },
     [](const SceneDef& d) { return d.belt.tensioning == Tensioning::strain; }, nullptr},
    {"belt", "direction", K::other, "", {}, "`\"cw\"`", W::ours, R::none,
     "direction of travel round the loop, \"cw\" or \"ccw\" (the default turns as the paper's driver)", nullptr,
     nullptr,
     [](const SceneDef& d, const PulleyDef&) -> std::string { return d.belt.loop_sense < 0 ? "cw" : "ccw"; }},
    {"belt", "route", K::other, "", {}, "the order of pulleys", W::none, R::none,
     "pulley names in the order the belt visits them", nullptr, nullptr, nullptr},
    {"belt", "EA", K::number, "N", 1.52e5, "", W::reading, R::positive,
     "axial rigidity, the paper's c_tra; per SDE k = EA/l0, l0 the rest length of an element",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.EA; }, rigidity, nullptr},
    {"belt", "EI", K::number, "N·m²", 0.026, "", W::reading, R::positive,
     "bending rigidity, the paper's c_tor; per SDE k_t = EI/l0",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.EI; }, rigidity, nullptr},
    {"belt", "axial_damping", K::number, "N·s", 20.5, "", W::reading, R::non_negative,
     "the paper's b_tra, per length; per SDE c = axial_damping/l0",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.axial_damping; }, rigidity, nullptr},
    {"belt", "bending_damping", K::number, "N·m·s/rad", 0.05, "", W::paper, R::non_negative,
     "the paper's b_tor, per SDE (bending_viscosity gives it per length)",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.bending_damping; },
     [](const SceneDef& d) { return rigidity(d) && !d.belt.bending_viscosity; }, nullptr},
    {"belt", "bending_viscosity", K::number, "N·m²·s", {}, "", W::none, R::non_negative,
     "per length, instead of bending_damping; per SDE c_t = bending_viscosity/l0",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.bending_viscosity; }, rigidity, nullptr},
    {"belt", "sde", K::other, "", {}, "", W::none, R::none,
     "instead of EA, EI and the dampings: { k, c, kt, ct } per SDE (table below)", nullptr, nullptr, nullptr},
    {"belt", "e_tra", K::number, "", 1, "", W::ours, R::exponent, "exponent of the axial spring",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.e_tra; }, nullptr, nullptr},
    {"belt", "e_tor", K::number, "", 1, "", W::ours, R::exponent, "exponent of the bending spring",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.e_tor; }, nullptr, nullptr},
    {"belt", "mass_per_length", K::number, "kg/m", 0.096, "", W::paper, R::positive,
     "the paper's rho, per metre of unstretched belt",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.mass_per_length; }, nullptr, nullptr},
    {"belt", "mu", K::other, "", 1, "", W::paper, R::friction_coefficient,
     "effective friction coefficient of the belt on a pulley: a number, a list (one per element) or "
     "function(site) return μ end",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.mu; }, nullptr,
     [](const SceneDef& d, const PulleyDef&) -> std::string {
       return d.belt.mu_at ? "function of where each element starts"
              : d.belt.mu_per_element.empty() ? ""
                                              : "one value per element";
     }},

    {"belt", "rib_angle", K::number, "°", 40, "", W::ours, R::positive,
     "the V-ribs' included angle β, in degrees (40° for PK belts); with mu_flank the effective μ = "
     "mu_flank/sin(β/2); outside 20°-60° the run's first lines warn (below 3: in radians?)",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.rib_angle; }, nullptr, nullptr},
    {"belt", "mu_flank", K::number, "", {}, "", W::none, R::friction_coefficient,
     "friction coefficient of the rib flanks, instead of mu: mu = mu_flank/sin(rib_angle/2) (the paper's μ = 1 is "
     "already the effective one)",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.mu_flank; }, nullptr, nullptr},

    // ---- belt.sde = {...}: all four, instead of the rigidities ----
    {"belt.sde", "k", K::number, "N/m", {}, "", W::none, R::positive, "axial stiffness per SDE",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.k; }, per_sde, nullptr},
    {"belt.sde", "c", K::number, "N·s/m", {}, "", W::none, R::non_negative, "axial damping per SDE",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.c; }, per_sde, nullptr},
    {"belt.sde", "kt", K::number, "N·m/rad", {}, "", W::none, R::positive, "bending stiffness per SDE",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.kt; }, per_sde, nullptr},
    {"belt.sde", "ct", K::number, "N·m·s/rad", {}, "", W::none, R::non_negative, "bending damping per SDE",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.belt.ct; }, per_sde, nullptr},

    // ---- contact = {...}: eq. 2, each constant per element or per metre of pitch ----
    {"contact", "c1", K::number, "N/m²", 3.0256e9, "", W::paper, R::non_negative,
     "the paper's c1, quadratic stiffness per element",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.contact.c1; },
     [](const SceneDef& d) { return !d.contact_per_length.c1; }, nullptr},
    {"contact", "c1_per_length", K::number, "N/m³", {}, "", W::none, R::non_negative,
     "c1 per metre of pitch, instead of c1: per element c1 = c1_per_length·l",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.contact_per_length.c1; }, nullptr, nullptr},
    {"contact", "c2", K::number, "N/m", 6.5e5, "", W::paper, R::positive,
     "the paper's c2, linear stiffness per element",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.contact.c2; },
     [](const SceneDef& d) { return !d.contact_per_length.c2; }, nullptr},
    {"contact", "c2_per_length", K::number, "N/m²", {}, "", W::none, R::positive,
     "c2 per metre of pitch, instead of c2: per element c2 = c2_per_length·l",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.contact_per_length.c2; }, nullptr, nullptr},
    {"contact", "damping", K::number, "N·s/m", 300, "", W::paper, R::non_negative,
     "the paper's b, damping per element",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.contact.b; },
     [](const SceneDef& d) { return !d.contact_per_length.b; }, nullptr},
    {"contact", "damping_per_length", K::number, "N·s/m²", {}, "", W::none, R::non_negative,
     "b per metre of pitch, instead of damping: per element b = damping_per_length·l",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.contact_per_length.b; }, nullptr, nullptr},
    {"contact", "p_max", K::number, "m", 1e-3, "", W::paper, R::positive,
     "the paper's p_max, the depth at which the damping is full (a depth: the same either way)",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.contact.p_max; }, nullptr, nullptr},

    // ---- friction = {...} ----
    {"friction", "dv", K::number, "m/s", 1e-5, "", W::paper, R::slip_band,
     "the paper's Δv, the slip speed at which μ reaches its kinetic value",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.dv; }, nullptr, nullptr},
    {"friction", "law", K::other, "", {}, "`\"threlfall\"`", W::paper, R::none,
     "\"threlfall\" (the paper's: μ_i·sat(v_T/Δv)), \"stribeck\" or \"lugre\" (docs/friction.md)", nullptr, nullptr,
     [](const SceneDef& d, const PulleyDef&) -> std::string { return friction_law_name(d.friction.law); }},
    {"friction", "static_ratio", K::number, "", 1.3, "", W::ours, R::positive,
     "stribeck, lugre: μ_s/μ_k, the peak of the curve at rest over the element's kinetic μ (belt.mu)",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.static_ratio; }, stribeck, nullptr},
    {"friction", "stribeck_speed", K::number, "m/s", 0.01, "", W::ours, R::positive,
     "stribeck, lugre: v_s, the slip speed over which μ falls from μ_s towards μ_k",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.stribeck_speed; }, stribeck, nullptr},
    {"friction", "exponent", K::number, "", 2, "", W::ours, R::positive,
     "stribeck, lugre: δ, the shape of the fall, exp(-(v_T/v_s)^δ) for v_T > 0",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.exponent; }, stribeck, nullptr},
    {"friction", "viscous", K::number, "s/m", 0, "", W::ours, R::non_negative,
     "stribeck, lugre: μ_v, the viscous term: μ grows by μ_v·v_T",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.viscous; }, stribeck, nullptr},
    {"friction", "bristle_stiffness", K::number, "1/m", 1e5, "", W::ours, R::positive,
     "lugre: σ0, μ per metre of bristle deflection (μ_s/σ0 is the deflection before sliding)",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.bristle_stiffness; }, lugre, nullptr},
    {"friction", "bristle_damping", K::number, "s/m", 0.3, "", W::ours, R::non_negative,
     "lugre: σ1, μ per m/s of the deflection's rate",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.bristle_damping; }, lugre, nullptr},
    {"friction", "release_time", K::number, "s", 1e-3, "", W::ours, R::positive,
     "lugre: τ, the time in which an element's deflection relaxes once it leaves a pulley",
     [](SceneDef& d, PulleyDef&) -> Slot { return &d.friction.release_time; }, lugre, nullptr},

    {"friction", "segments", K::other, "", {}, "none: the whole belt", W::none, R::none,
     "belt segments with a law of their own: a list of tables (below)", nullptr, nullptr, nullptr},

    // ---- friction.segments = { {...}, ... }: their own code reads them, with the friction keys ----
    {"friction.segments", "from", K::other, "m", {}, "", W::none, R::none,
     "where the segment begins along the belt (site.s of the elements, as belt.mu functions); required",
     nullptr, nullptr, nullptr},
    {"friction.segments", "to", K::other, "m", {}, "", W::none, R::none,
     "where it ends (from > to wraps round past s = 0); required", nullptr, nullptr, nullptr},
    {"friction.segments", "law", K::other, "", {}, "the friction table's", W::none, R::none,
     "the segment's law; every other key of the friction table (but dv and segments) too, each defaulting to "
     "the friction table's value",
     nullptr, nullptr, nullptr},

    // ---- spray = { {...}, ... }: zones that wet the belt (model/spray.hpp); read by their own code ----
    {"spray", "centre", K::other, "m", {}, "", W::none, R::none, "{x, y} of the zone's circle; required", nullptr,
     nullptr, nullptr},
    {"spray", "radius", K::number, "m", {}, "", W::none, R::positive,
     "the circle's radius: an element whose centre is inside it while it sprays is wetted; required", nullptr,
     nullptr, nullptr},
    {"spray", "mu", K::number, "", {}, "", W::none, R::friction_coefficient,
     "the friction coefficient a wetted element takes; required", nullptr, nullptr, nullptr},
    {"spray", "from", K::number, "s", 0, "", W::ours, R::non_negative, "when it starts spraying", nullptr, nullptr,
     nullptr},
    {"spray", "to", K::number, "s", {}, "never: to the run's end", W::none, R::non_negative,
     "when it stops spraying (after from)", nullptr, nullptr, nullptr},
    {"spray", "drying_length", K::number, "m", {}, "", W::none, R::positive,
     "the travel over which an element that leaves the spray dries back to its own μ (linearly); required",
     nullptr, nullptr, nullptr},
};
// clang-format on

}  // namespace

std::string Parameter::dotted() const {
  return table == "scene" ? std::string(key) : std::string(table) + "." + std::string(key);
}

std::span<const Parameter> parameters() { return kParameters; }

std::vector<const Parameter*> parameters_of(std::string_view table) {
  std::vector<const Parameter*> out;
  for (const Parameter& p : kParameters)
    if (p.table == table) out.push_back(&p);
  return out;
}

std::vector<std::string> keys_of(std::string_view table) {
  std::vector<std::string> out;
  for (const Parameter* p : parameters_of(table)) out.emplace_back(p->key);
  return out;
}

const Parameter* find_parameter(std::string_view dotted) {
  for (const Parameter& p : kParameters)
    if (p.dotted() == dotted) return &p;
  return nullptr;
}

double parameter_default(std::string_view dotted) {
  const Parameter* p = find_parameter(dotted);
  if (!p || !p->fallback) throw std::logic_error("no default for the parameter '" + std::string(dotted) + "'");
  return *p->fallback;
}

std::optional<double> value_of(const Parameter& par, const SceneDef& d, const PulleyDef* p) {
  if (!par.slot) return std::nullopt;
  // the slot's accessor takes mutable references; it only takes an address here
  PulleyDef none;
  const Slot s = par.slot(const_cast<SceneDef&>(d), const_cast<PulleyDef&>(p ? *p : none));
  if (auto* x = std::get_if<double*>(&s)) return **x;
  if (auto* i = std::get_if<int*>(&s)) return **i;
  if (auto* o = std::get_if<std::optional<double>*>(&s)) return **o;
  return std::nullopt;
}

std::string_view whose_text(Whose w) {
  switch (w) {
    case Whose::paper: return "the paper's";
    case Whose::reading: return "the paper's, read as docs/model.md says";
    case Whose::ours: return "ours";
    case Whose::none: break;
  }
  return "";
}

std::string_view rule_text(Rule r) {
  switch (r) {
    case Rule::positive: return "must be > 0";
    case Rule::non_negative: return "must be >= 0";
    case Rule::exponent: return "must be >= 1 (below 1 the stiffness is infinite at zero)";
    case Rule::at_least_three: return "must be >= 3";
    case Rule::friction_coefficient:
      return "must be in [0, 10]: a friction coefficient (a rib's effective one stays below 5; a larger one only "
             "shrinks the steps, the friction band's stiffness growing with it)";
    case Rule::slip_band:
      return "must be in (0, 1] m/s: μ reaches μ_i only at a slip of dv and a loaded belt creeps at up to dv, so a "
             "band as wide as belt speeds (a few m/s and up) is no friction (the paper's is 1e-5 m/s)";
    case Rule::pulley_radius:
      return "must be at most 5 m: lengths are in metres (a 100 mm radius is 0.1); belt pulleys are smaller";
    case Rule::strain:
      return "must be > 0 and below 0.5: strain is a fraction: 0.009 = 0.9 % (a PK belt is mounted at a few "
             "tenths of a per cent; no belt stretches by half its length)";
    case Rule::finite: return "must be a finite number";
    case Rule::none: break;
  }
  return "";
}

}  // namespace beltsim
