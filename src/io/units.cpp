#include "io/units.hpp"

#include <array>
#include <utility>

namespace beltsim {

namespace {

// last dotted component → unit (docs/outputs.md; element and pulley fields of the Lua API)
constexpr std::array<std::pair<std::string_view, std::string_view>, 46> kUnits{{
    {"t", "s"},
    // pulleys
    {"omega", "rad/s"},
    {"angle", "rad"},
    {"torque", "N·m"},
    {"belt_torque", "N·m"},
    {"hub_load", "N"},
    {"arm_angle", "rad"},
    {"arm_rate", "rad/s"},
    {"rotor_angle", "rad"},
    {"rotor_speed", "rad/s"},
    {"windup", "rad"},
    {"coupling_torque", "N·m"},
    {"torque_mean", "N·m"},
    {"belt_torque_mean", "N·m"},
    {"contact_arc", "m"},
    {"slip_arc", "m"},
    {"stick_arc", "m"},
    {"creep", ""},
    {"slip_speed", "m/s"},
    {"creep_pitch", ""},
    // spans and the probed element
    {"tension", "N"},
    {"tension_mean", "N"},
    {"sde_force", "N"},
    {"normal_force", "N"},
    {"friction_force", "N"},
    {"slip_velocity", "m/s"},
    // element fields
    {"x", "m"},
    {"y", "m"},
    {"s", "m"},
    {"phi", "rad"},
    {"normal", "N"},
    {"friction", "N"},
    {"slip", "m/s"},
    {"mu", ""},
    // the live simulation: wall time of a run, sim:energy() fields
    {"wall", "s"},
    {"kinetic", "J"},
    {"sde", "J"},
    {"bending", "J"},
    {"contact", "J"},
    {"gravity", "J"},
    {"mechanical", "J"},
    {"work_torques", "J"},
    {"dissipated_axial", "J"},
    {"dissipated_bending", "J"},
    {"dissipated_contact", "J"},
    {"dissipated_friction", "J"},
}};

}  // namespace

std::string unit_of(std::string_view column) {
  const size_t dot = column.rfind('.');
  if (dot != std::string_view::npos && column.substr(0, column.find('.')) == "energy") return "J";
  const std::string_view key = dot == std::string_view::npos ? column : column.substr(dot + 1);
  for (const auto& [name, unit] : kUnits)
    if (name == key) return std::string(unit);
  return "";
}

}  // namespace beltsim
