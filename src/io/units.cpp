#include "io/units.hpp"

#include <array>
#include <utility>

#include "io/csv_writer.hpp"
#include "io/input_file.hpp"
#include "io/output_dir.hpp"

namespace beltsim {

namespace {

// last dotted component → unit (docs/outputs.md; element and pulley fields of the Lua API)
constexpr std::array<std::pair<std::string_view, std::string_view>, 51> kUnits{{
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
    {"slip_pitch", "m/s"},
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
    {"arm", "J"},
    {"coupling", "J"},
    {"mechanical", "J"},
    {"work_torques", "J"},
    {"dissipated_axial", "J"},
    {"dissipated_bending", "J"},
    {"dissipated_contact", "J"},
    {"dissipated_friction", "J"},
    {"dissipated_arms", "J"},
    {"dissipated_couplings", "J"},
}};

// scene:run{}'s result table (script/lua_scene_run.cpp, docs/lua-api.md), its fields flattened as
// a sweep's quick form writes them, each with the name kUnits gives its unit under, or "" for a
// count or a ratio (dimensionless); a name ending in '.' stands for every field under it
// (omega.<pulley>). Its text and booleans (interrupted, csv, parameters, check.over, check.shared,
// check.failed) have no unit and are not here.
constexpr std::array<std::pair<std::string_view, std::string_view>, 15> kRunResult{{
    {"t", "t"},
    {"wall", "wall"},
    {"steps", ""},
    {"rejected", ""},
    {"rhs", ""},
    {"jacobians", ""},
    {"factorizations", ""},
    {"frames", ""},
    {"omega.", "omega"},
    // check = true: relative errors and their bounds, the companion's steps over the run's
    {"check.speed", ""},
    {"check.tension", ""},
    {"check.limit_speed", ""},
    {"check.limit_tension", ""},
    {"check.steps_ratio", ""},
    {"check.warned_t", "t"},
}};

// unit -> scale (header: unit_scale). Each is the size of the quantity on the paper's drive and
// on an accessory drive, at the low end of each range (a value near 0 is compared at a size the
// quantity takes): span tensions and hub loads 100 N to 2 kN, pulley torques 10 to 100 N·m,
// pulley speeds 10 rad/s (100 rpm, starting) to 600 rad/s, arcs and positions 0.05 to 0.5 m, slip speeds 0.01 to 1 m/s,
// energies 10 to 1000 J; angles in radians; creep and slip ratios of 1e-3 to 3e-2 (dimensionless)
constexpr std::array<std::pair<std::string_view, double>, 9> kScales{{
    {"s", 1},
    {"rad/s", 10},
    {"rad", 1},
    {"N·m", 10},
    {"N", 100},
    {"m", 0.1},
    {"m/s", 1},
    {"J", 10},
    {"", 1e-2},
}};

}  // namespace

std::optional<std::string> bracketed_unit(std::string_view header) {
  const std::size_t open = header.rfind('[');
  if (!header.empty() && header.back() == ']' && open != std::string_view::npos)
    return typed_unit(header.substr(open + 1, header.size() - open - 2));
  return std::nullopt;
}

std::string header_unit(std::string_view header) {
  if (std::optional<std::string> u = bracketed_unit(header)) return *u;
  return unit_of(header);
}

std::string units_file_name(const std::string& csv) {
  const std::string stem =
      csv.size() > 4 && csv.compare(csv.size() - 4, 4, ".csv") == 0 ? csv.substr(0, csv.size() - 4) : csv;
  return stem + "_units.csv";
}

void write_units_file(const OutputDir& dir, const std::string& csv, const ColumnUnits& columns) {
  std::string text = "column,unit\n";
  for (const auto& [column, unit] : columns)
    text += csv_text(column) + "," + (unit ? csv_text(unit->empty() ? "1" : *unit) : std::string()) + "\n";
  write_file_whole(dir, units_file_name(csv), text);
}

std::optional<ColumnUnits> read_units_file(const std::string& csv) {
  std::string text;
  try {
    text = InputFile(units_file_name(csv)).read_rest();
  } catch (const InputFileError&) {
    return std::nullopt;
  }
  const std::vector<std::vector<std::string>> rows = csv_rows(text);
  if (rows.empty() || rows[0] != std::vector<std::string>{"column", "unit"}) return std::nullopt;
  ColumnUnits columns;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].size() != 2) return std::nullopt;
    const std::string& unit = rows[k][1];
    columns.emplace_back(rows[k][0], unit.empty() ? std::nullopt : std::optional<std::string>(typed_unit(unit)));
  }
  return columns;
}

double unit_scale(std::string_view unit) {
  for (const auto& [name, scale] : kScales)
    if (name == unit) return scale;
  return 1;
}

std::string typed_unit(std::string_view typed) {
  if (typed == "N.m" || typed == "N*m" || typed == "Nm" || typed == "N m") return "N·m";
  if (typed == "1" || typed == "-") return "";
  return std::string(typed);
}

std::optional<std::string> known_unit(std::string_view column) {
  const size_t dot = column.rfind('.');
  if (dot != std::string_view::npos && column.substr(0, column.find('.')) == "energy") return "J";
  const std::string_view key = dot == std::string_view::npos ? column : column.substr(dot + 1);
  for (const auto& [name, unit] : kUnits)
    if (name == key) return std::string(unit);
  return std::nullopt;
}

std::string unit_of(std::string_view column) {
  return known_unit(column).value_or("");
}

std::vector<std::pair<std::string, std::string>> run_result_units(std::string_view prefix) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [name, quantity] : kRunResult)
    if (name.size() > prefix.size() && name.substr(0, prefix.size()) == prefix && name.back() != '.')
      out.emplace_back(std::string(name.substr(prefix.size())), *run_result_unit(name));
  return out;
}

std::optional<std::string> run_result_unit(std::string_view field) {
  for (const auto& [name, quantity] : kRunResult)
    if (name == field || (name.back() == '.' && field.size() > name.size() && field.substr(0, name.size()) == name))
      return quantity.empty() ? std::string() : known_unit(quantity);
  return std::nullopt;
}

}  // namespace beltsim
