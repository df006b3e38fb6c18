// r:summary{ from, to, csv, plot } on a run's results and sim:summary{...} on a live simulation:
// the review figures of plot/summary.hpp as a Lua table (lua_summary.hpp).
#include "script/lua_summary.hpp"

#include <cmath>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>

#include "io/output_dir.hpp"
#include "io/units.hpp"
#include "plot/summary.hpp"
#include "script/context.hpp"
#include "script/lua_check.hpp"
#include "script/sandbox.hpp"
#include "script/sim_box.hpp"
#include "sim/run_settings.hpp"

namespace beltsim::script {

namespace {

namespace fs = std::filesystem;

constexpr const char* kResultsMeta = "beltsim.run_results";

// t[section][item][quantity] = value (t[section][quantity] for the window's and loss's figures),
// the window's figures at the top, each rotor's overrun intervals as { {from, to}, ... }
void push_figures(lua_State* L, const plot::Summary& s) {
  lua_newtable(L);
  const int top = lua_gettop(L);
  // a count as a Lua integer (301, not 301.0), the others as floats; with the figure's unit for
  // the console's printer (lua_check.hpp, set_unit)
  const auto set = [L](const plot::Figure& f) {
    if (f.count)
      lua_pushinteger(L, static_cast<lua_Integer>(f.value));
    else
      lua_pushnumber(L, f.value);
    lua_setfield(L, -2, f.quantity.c_str());
    if (!f.unit.empty()) set_unit(L, -1, f.quantity, f.unit);
  };
  for (const plot::Figure& f : s.figures) {
    if (f.section == "window") {
      set(f);
      continue;
    }
    if (lua_getfield(L, top, f.section.c_str()) != LUA_TTABLE) {
      lua_pop(L, 1);
      lua_newtable(L);
      lua_pushvalue(L, -1);
      lua_setfield(L, top, f.section.c_str());
    }
    if (!f.item.empty()) {
      if (lua_getfield(L, -1, f.item.c_str()) != LUA_TTABLE) {
        lua_pop(L, 1);
        lua_newtable(L);
        lua_pushvalue(L, -1);
        lua_setfield(L, -3, f.item.c_str());
      }
    }
    set(f);
    lua_settop(L, top);
  }
  for (const plot::Overrun& o : s.overruns) {
    lua_getfield(L, top, "rotors");
    lua_getfield(L, -1, o.pulley.c_str());
    lua_createtable(L, static_cast<int>(o.intervals.size()), 0);
    for (size_t k = 0; k < o.intervals.size(); ++k) {
      lua_createtable(L, 2, 0);
      lua_pushnumber(L, o.intervals[k].first), lua_rawseti(L, -2, 1);
      lua_pushnumber(L, o.intervals[k].second), lua_rawseti(L, -2, 2);
      lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
    }
    lua_setfield(L, -2, "overrun");
    lua_settop(L, top);
  }
  const std::string table = plot::summary_table(s);
  lua_pushstring(L, table.c_str());
  lua_setfield(L, top, "table");
}

// the summary of the outputs in dir with the options in the table at idx (or none); relative
// csv and plot paths lie inside dir, as sim:plot's
int summary(lua_State* L, const Context& ctx, const std::string& what, const std::string& dir, int idx) {
  double from = -INFINITY, to = INFINITY;
  std::optional<std::string> csv, png;
  if (!lua_isnoneornil(L, idx)) {
    require_table(L, idx, what);
    check_keys(L, idx, what, {"from", "to", "csv", "plot"});
    if (auto v = opt_number(L, idx, "from", what)) from = *v;
    if (auto v = opt_number(L, idx, "to", what)) to = *v;
    csv = opt_string(L, idx, "csv", what);
    png = opt_string(L, idx, "plot", what);
    if (const std::string bad = png ? png_name_problem(*png) : ""; !bad.empty())
      fail_on(L, what + ".plot", "'" + *png + "': " + bad);
  }
  if (!(from <= to))
    fail(L, what + ": from = " + std::to_string(from) + " s lies after to = " + std::to_string(to) + " s");
  auto inside = [&](std::optional<std::string>& file) {
    if (!file) return;
    if (file->empty()) fail(L, what + ": an empty path");
    *file = output_path(dir, *file);
    if (const std::string r = output_refusal(ctx, what, *file, true); !r.empty()) fail(L, r);
  };
  inside(csv);
  inside(png);
  plot::Summary s;
  guarded(L, what.c_str(), [&] {
    s = plot::summarize(dir, from, to);
    // each output asked for is written (its missing folders made); the first that cannot be is
    // raised once the other has been tried
    std::exception_ptr failed;
    const auto attempt = [&failed](const auto& write) {
      try {
        write();
      } catch (const std::exception&) {
        if (!failed) failed = std::current_exception();
      }
    };
    if (csv) attempt([&] { plot::write_summary_csv(s, *csv); });
    if (png) attempt([&] { plot::plot_summary(s, *png); });
    if (failed) std::rethrow_exception(failed);
  });
  push_figures(L, s);
  if (csv) lua_pushstring(L, csv->c_str()), lua_setfield(L, -2, "csv");
  if (png) lua_pushstring(L, png->c_str()), lua_setfield(L, -2, "plot");
  return 1;
}

// r:summary{...}: the folder of r.csv
int l_results_summary(lua_State* L) {
  const auto* ctx = static_cast<const Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  check_args(L, "r:summary", {{"results", kTable}, {"{from, to, csv, plot}", kTable, true}});
  lua_getfield(L, 1, "csv");
  if (lua_type(L, -1) != LUA_TSTRING) fail(L, "r:summary: r.csv is not a run's timeseries.csv path");
  const std::string dir = fs::path(lua_tostring(L, -1)).parent_path().string();
  lua_pop(L, 1);
  return summary(L, *ctx, "r:summary", dir.empty() ? "." : dir, 2);
}

}  // namespace

void set_results_methods(lua_State* L, Context* ctx) {
  if (luaL_newmetatable(L, kResultsMeta)) {
    lua_newtable(L);
    lua_pushlightuserdata(L, ctx);
    lua_pushcclosure(L, l_results_summary, 1);
    lua_setfield(L, -2, "summary");
    lua_setfield(L, -2, "__index");
    // the units of its fields (io/units.cpp kRunResult) for the console's printer (kUnitsField)
    lua_newtable(L);
    for (const char* f : {"t", "wall", "steps", "rejected", "rhs", "jacobians", "factorizations", "frames"})
      if (const std::optional<std::string> unit = run_result_unit(f))
        lua_pushstring(L, unit->c_str()), lua_setfield(L, -2, f);
    lua_setfield(L, -2, kUnitsField);
  }
  lua_setmetatable(L, -2);
}

int l_sim_summary(lua_State* L) {
  const Simulation& s = live(L, "summary", {{"{from, to, csv, plot}", kTable, true}});
  const SimBox& box = *static_cast<SimBox*>(lua_touserdata(L, 1));
  return summary(L, *box.ctx, "sim:summary", s.settings().out_dir, 2);
}

}  // namespace beltsim::script
