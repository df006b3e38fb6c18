#include "script/lua_sweep.hpp"

#include <algorithm>
#include <new>

#include "io/number_text.hpp"
#include "script/context.hpp"
#include "script/lua_check.hpp"

namespace beltsim::script {

namespace {

bool is_name(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// the string keys of the table at idx, sorted (a Lua table has no order of its own)
std::vector<std::string> sorted_names(lua_State* L, int idx, const std::string& what) {
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING || !is_name(lua_tostring(L, -1)))
      fail_on(L, what, std::string("the parameters are named by Lua names (p.NAME), got a key ") + type_name(L, -1));
    names.emplace_back(lua_tostring(L, -1));
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) fail_on(L, what, "name at least one parameter");
  return names;
}

sweep::Value to_value(lua_State* L, int idx, const std::string& what) {
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER: {
      if (lua_isinteger(L, idx)) return static_cast<long long>(lua_tointeger(L, idx));
      const double x = lua_tonumber(L, idx);
      if (!std::isfinite(x)) fail_on(L, what, std::string("a finite number expected, got ") + number_text(x));
      return x;
    }
    case LUA_TBOOLEAN:
      return static_cast<bool>(lua_toboolean(L, idx));
    case LUA_TSTRING:
      return to_string(L, idx, what);
    default:
      fail_on(L, what, std::string("a number, string or boolean expected, got ") + type_name(L, idx));
  }
}

std::vector<sweep::Point> read_grid(lua_State* L, int g) {
  require_table(L, g, "sweep.grid");
  sweep::Grid grid;
  grid.names = sorted_names(L, g, "sweep.grid");
  for (const std::string& name : grid.names) {
    const std::string w = "sweep.grid." + name;
    lua_getfield(L, g, name.c_str());
    if (!lua_istable(L, -1)) fail_on(L, w, std::string("a list of values expected, got ") + type_name(L, -1));
    const size_t n = check_sequence(L, lua_gettop(L), w).size();
    std::vector<sweep::Value> values;
    for (size_t k = 1; k <= n; ++k) {
      lua_rawgeti(L, -1, static_cast<lua_Integer>(k));
      values.push_back(to_value(L, -1, w + "[" + std::to_string(k) + "]"));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    grid.values.push_back(std::move(values));
  }
  try {
    return sweep::grid_points(grid);
  } catch (const std::invalid_argument& e) {
    // an error about one list ("grid.load: no values") at that list's line, spelt as the others
    // (sweep.grid.load[2]: ...): fail finds the path at the start of the message
    const std::string m = e.what();
    fail(L, m.rfind("grid.", 0) == 0 ? "sweep." + m : "sweep: " + m);
  }
}

std::vector<sweep::Point> read_samples(lua_State* L, int s) {
  require_table(L, s, "sweep.samples");
  check_keys(L, s, "sweep.samples", {"n", "ranges", "seed"});
  sweep::Samples samples;
  if (!field(L, s, "n")) fail_on(L, "sweep.samples.n", "the number of points is missing");
  if (!lua_isinteger(L, -1)) fail_on(L, "sweep.samples.n", "a whole number expected, got " + type_name(L, -1));
  samples.n = static_cast<long long>(lua_tointeger(L, -1));
  lua_pop(L, 1);
  if (field(L, s, "seed")) {
    if (!lua_isinteger(L, -1)) fail_on(L, "sweep.samples.seed", "a whole number expected, got " + type_name(L, -1));
    samples.seed = static_cast<std::uint64_t>(lua_tointeger(L, -1));
    lua_pop(L, 1);
  }
  if (!field(L, s, "ranges")) fail_on(L, "sweep.samples.ranges", "{ NAME = {lo, hi}, ... } is missing");
  const int r = lua_gettop(L);
  require_table(L, r, "sweep.samples.ranges");
  samples.names = sorted_names(L, r, "sweep.samples.ranges");
  for (const std::string& name : samples.names) {
    const std::string w = "sweep.samples.ranges." + name;
    lua_getfield(L, r, name.c_str());
    if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2)
      fail_on(L, w, std::string("{lo, hi} expected, got ") + type_name(L, -1));
    double b[2];
    for (int k = 0; k < 2; ++k) {
      lua_rawgeti(L, -1, k + 1);
      b[k] = to_number(L, -1, w);
      if (!std::isfinite(b[k])) fail_on(L, w, "finite bounds expected");
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    samples.ranges.emplace_back(b[0], b[1]);
  }
  lua_pop(L, 1);
  try {
    return sweep::sample_points(samples);
  } catch (const std::invalid_argument& e) {
    fail(L, std::string("sweep.") + e.what());
  }
}

// beltsim.sweep{ grid = { NAME = {v1, v2, ...}, ... } | samples = { n =, ranges = { NAME = {lo, hi} }, seed = },
//                run = function(p) ... return { figure = value, ... } end } -> a sweep
int l_sweep(lua_State* L) {
  check_args(L, "beltsim.sweep", {{"{grid | samples, run}", kTable}});
  check_keys(L, 1, "sweep", {"grid", "samples", "run"});
  const bool grid = has(L, 1, "grid"), samples = has(L, 1, "samples");
  if (grid == samples) fail_on(L, "sweep", "give grid = {...} or samples = {...}, one of them");
  if (!field(L, 1, "run")) fail_on(L, "sweep.run", "function(p) expected, got nil");
  if (!lua_isfunction(L, -1)) fail(L, std::string("sweep.run: function(p) expected, got ") + type_name(L, -1));
  lua_pop(L, 1);
  field(L, 1, grid ? "grid" : "samples");
  std::vector<sweep::Point> points = grid ? read_grid(L, lua_gettop(L)) : read_samples(L, lua_gettop(L));
  lua_pop(L, 1);
  auto* box = static_cast<SweepBox*>(lua_newuserdatauv(L, sizeof(SweepBox), 1));
  new (box) SweepBox{std::move(points)};
  luaL_setmetatable(L, kSweepMeta);
  field(L, 1, "run");
  lua_setiuservalue(L, -2, 1);
  return 1;
}

int l_sweep_gc(lua_State* L) {
  static_cast<SweepBox*>(luaL_checkudata(L, 1, kSweepMeta))->~SweepBox();
  return 0;
}

int l_sweep_tostring(lua_State* L) {
  const auto* box = static_cast<SweepBox*>(luaL_checkudata(L, 1, kSweepMeta));
  lua_pushfstring(L, "beltsim.sweep (%d points)", static_cast<int>(box->points.size()));
  return 1;
}

}  // namespace

void open_sweep(lua_State* L, Context* /*ctx*/) {
  luaL_newmetatable(L, kSweepMeta);
  lua_pushcfunction(L, l_sweep_gc), lua_setfield(L, -2, "__gc");
  lua_pushcfunction(L, l_sweep_tostring), lua_setfield(L, -2, "__tostring");
  lua_pushliteral(L, "beltsim.sweep"), lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
  lua_pushcfunction(L, l_sweep), lua_setfield(L, -2, "sweep");
}

}  // namespace beltsim::script
