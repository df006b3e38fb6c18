// sim:modes{...}: the drive's modes about the simulation's state now (sim/modes.hpp, docs/modes.md),
// as a table, and on request as a CSV and pictures of the mode shapes (sim_box.hpp).
#include <cstdio>
#include <utility>

#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "render/mode_frames.hpp"
#include "script/lua_check.hpp"
#include "script/lua_sim.hpp"
#include "script/sandbox.hpp"
#include "script/sim_box.hpp"
#include "sim/modes.hpp"

namespace beltsim::script {

// sim:modes{ fmin, fmax, transport, csv = "modes.csv", shapes = N, video = bool } -> { t, belt_speed,
// period, position_defect, velocity_defect, forced,
// groups = {...}, csv, pictures = {...}, [k] = { frequency, damping, decay, where, share = { group = s } } }
int l_modes(lua_State* L) {
  const char* where = "sim:modes";
  Simulation& s = live(L, "modes", {{"{fmin, fmax, csv, shapes, ...}", kTable, true}});
  SimBox& box = *static_cast<SimBox*>(lua_touserdata(L, 1));
  ModeSettings ms;
  std::string csv;
  render::ModePictures pics;
  pics.count = 0;
  if (!lua_isnoneornil(L, 2)) {
    check_keys(L, 2, where, {"fmin", "fmax", "transport", "csv", "shapes", "video"});
    if (auto v = opt_number(L, 2, "fmin", where)) ms.f_min = *v;
    if (auto v = opt_number(L, 2, "fmax", where)) ms.f_max = *v;
    if (auto v = opt_bool(L, 2, "transport", where)) ms.transport = *v;
    if (auto v = opt_string(L, 2, "csv", where)) csv = output_path(s.settings(), *v);
    if (auto v = opt_number(L, 2, "shapes", where)) {
      if (!(*v >= 0 && *v <= 1000 && *v == static_cast<int>(*v)))
        fail(L, std::string(where) + ": shapes must be a whole number of modes to draw, 0 to 1000 (got " +
                    number_text(*v) + ")");
      pics.count = static_cast<int>(*v);
    }
    if (auto v = opt_bool(L, 2, "video", where)) pics.video = *v;
  }
  if (!csv.empty())
    if (const std::string r = output_refusal(*box.ctx, where, csv, true); !r.empty()) fail(L, r);
  if (pics.count > 0) {
    char tag[40];
    std::snprintf(tag, sizeof tag, "modes_%.6f", s.now());
    pics.dir = output_path(s.settings(), tag);
    if (const std::string r = output_refusal(*box.ctx, where, pics.dir, true); !r.empty()) fail(L, r);
  }
  ModeAnalysis a;
  std::vector<std::string> drawn;
  guarded(L, where, [&] {
    a = analyze_modes(s.scene(), s.drive(), s.now(), s.state(), ms);
    if (!csv.empty()) {
      CsvWriter w(csv, mode_columns(a));
      for (size_t k = 0; k < a.modes.size(); ++k) w.row(mode_row(a, k));
    }
    drawn = render::draw_modes(s.scene(), s.drive(), s.state(), a, pics);
  });
  lua_createtable(L, static_cast<int>(a.modes.size()), 6);
  set_number(L, "t", a.t);
  set_number(L, "belt_speed", a.belt_speed);
  // a running belt's passing (0: at rest or slow, the state's Jacobian) and how far its motion
  // over it is from repeating itself
  set_number(L, "period", a.period);
  set_number(L, "position_defect", a.position_defect);
  set_number(L, "velocity_defect", a.velocity_defect);
  for (const auto& [f, unit] : {std::pair{"t", "s"}, std::pair{"belt_speed", "m/s"}, std::pair{"period", "s"}})
    set_unit(L, -1, f, unit);
  if (a.forced >= 0) {  // the pulley whose law changes in time now (ModeAnalysis::forced)
    lua_pushstring(L, s.scene().model.pulleys[a.forced].name.c_str());
    lua_setfield(L, -2, "forced");
  }
  lua_createtable(L, static_cast<int>(a.groups.size()), 0);
  for (size_t g = 0; g < a.groups.size(); ++g) {
    lua_pushstring(L, a.groups[g].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(g + 1));
  }
  lua_setfield(L, -2, "groups");
  if (!csv.empty()) {
    lua_pushstring(L, csv.c_str());
    lua_setfield(L, -2, "csv");
  }
  lua_createtable(L, static_cast<int>(drawn.size()), 0);
  for (size_t k = 0; k < drawn.size(); ++k) {
    lua_pushstring(L, drawn[k].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "pictures");
  for (size_t k = 0; k < a.modes.size(); ++k) {
    const Mode& m = a.modes[k];
    lua_createtable(L, 0, 6);
    set_number(L, "frequency", m.frequency);
    set_number(L, "damping", m.damping);
    set_number(L, "decay", -m.lambda.real());
    set_unit(L, -1, "frequency", "Hz"), set_unit(L, -1, "decay", "1/s");  // as the CSV's frequency_Hz, decay_1_s
    lua_pushstring(L, a.groups[m.dominant].c_str());
    lua_setfield(L, -2, "where");
    lua_createtable(L, 0, static_cast<int>(a.groups.size()));
    for (size_t g = 0; g < a.groups.size(); ++g) set_number(L, a.groups[g].c_str(), m.participation[g]);
    lua_setfield(L, -2, "share");
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  return 1;
}

}  // namespace beltsim::script
