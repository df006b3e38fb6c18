#include "script/lua_sweep.hpp"

#include <algorithm>
#include <new>

#include "io/number_text.hpp"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/limits.hpp"
#include "script/lua_check.hpp"

namespace beltsim::script {

namespace {

constexpr const char* kSweepMeta = "beltsim.Sweep";
constexpr const char* kLoadedSweep = "beltsim.loaded_sweep";  // registry: the sweep load_sweep read

struct SweepBox {
  std::vector<sweep::Point> points;
};

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
    fail(L, std::string("sweep: ") + e.what());
  }
}

std::vector<sweep::Point> read_samples(lua_State* L, int s) {
  require_table(L, s, "sweep.samples");
  check_keys(L, s, "sweep.samples", {"n", "ranges", "seed"});
  sweep::Samples samples;
  if (!field(L, s, "n")) fail_on(L, "sweep.samples.n", "the number of points is missing");
  if (!lua_isinteger(L, -1)) fail(L, std::string("sweep.samples.n: a whole number expected, got ") + type_name(L, -1));
  samples.n = static_cast<long long>(lua_tointeger(L, -1));
  lua_pop(L, 1);
  if (field(L, s, "seed")) {
    if (!lua_isinteger(L, -1))
      fail(L, std::string("sweep.samples.seed: a whole number expected, got ") + type_name(L, -1));
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

void push_value(lua_State* L, const sweep::Value& v) {
  std::visit(
      [L](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, long long>)
          lua_pushinteger(L, static_cast<lua_Integer>(x));
        else if constexpr (std::is_same_v<T, double>)
          lua_pushnumber(L, x);
        else if constexpr (std::is_same_v<T, bool>)
          lua_pushboolean(L, x);
        else
          lua_pushlstring(L, x.data(), x.size());
      },
      v);
}

// the table at idx as figures: NAME = number | string | boolean | table (NAME.KEY ...), keys sorted
void flatten(lua_State* L, int idx, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& out,
             int depth) {
  idx = lua_absindex(L, idx);
  std::vector<std::string> keys;
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TNUMBER && lua_isinteger(L, -1))
      keys.push_back(std::to_string(lua_tointeger(L, -1)));
    else if (lua_type(L, -1) == LUA_TSTRING)
      keys.emplace_back(lua_tostring(L, -1));
    else
      throw std::runtime_error("run(p) returned " + (prefix.empty() ? std::string("a table") : prefix) +
                               " with a key that is not a name: " + type_name(L, -1));
  }
  std::sort(keys.begin(), keys.end());
  for (const std::string& k : keys) {
    const std::string name = prefix + k;
    lua_pushstring(L, k.c_str());
    if (lua_rawget(L, idx) == LUA_TNIL) {  // an integer key
      lua_pop(L, 1);
      lua_rawgeti(L, idx, std::stoll(k));
    }
    switch (lua_type(L, -1)) {
      case LUA_TNUMBER:
        out.emplace_back(
            name, lua_isinteger(L, -1) ? std::to_string(lua_tointeger(L, -1)) : number_text(lua_tonumber(L, -1)));
        break;
      case LUA_TBOOLEAN:
        out.emplace_back(name, lua_toboolean(L, -1) ? "true" : "false");
        break;
      case LUA_TSTRING:
        out.emplace_back(name, lua_tostring(L, -1));
        break;
      case LUA_TTABLE:
        if (depth > 8) throw std::runtime_error("run(p) returned tables nested deeper than 8 at " + name);
        flatten(L, -1, name + ".", out, depth + 1);
        break;
      default:
        throw std::runtime_error("run(p) returned " + name + " = a " + type_name(L, -1) +
                                 ": numbers, strings, booleans or tables of them expected");
    }
    lua_pop(L, 1);
  }
}

// the status of a failed call: the run's divergence when that is what ended it
std::string failed_status(const Context& ctx, const std::string& message) {
  if (ctx.divergence && message.find(ctx.divergence->second) != std::string::npos)
    return "diverged at t = " + number_text(ctx.divergence->first) + " s";
  return sweep::error_status(message);
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

std::vector<sweep::Point> load_sweep(Interpreter& lua, const std::string& path) {
  lua_State* L = lua.state();
  lua.run_file(path, 1);
  auto* box = static_cast<SweepBox*>(luaL_testudata(L, -1, kSweepMeta));
  if (!box) {
    const std::string got = type_name(L, -1);
    lua_settop(L, 0);
    throw ScriptError(path + ": a sweep file ends with `return beltsim.sweep{...}`; it returned " + got);
  }
  std::vector<sweep::Point> points = box->points;
  lua_setfield(L, LUA_REGISTRYINDEX, kLoadedSweep);
  lua_settop(L, 0);
  return points;
}

sweep::PointResult run_sweep_point(Interpreter& lua, const std::string& path, const sweep::Point& p,
                                   const std::string& point_dir) {
  lua_State* L = lua.state();
  Context& ctx = lua.context();
  ctx.default_out = point_dir;
  ctx.divergence.reset();
  begin_call(L);
  lua_getfield(L, LUA_REGISTRYINDEX, kLoadedSweep);
  lua_getiuservalue(L, -1, 1);
  lua_remove(L, -2);
  lua_createtable(L, 0, static_cast<int>(p.params.size()));
  for (const auto& [name, v] : p.params) push_value(L, v), lua_setfield(L, -2, name.c_str());
  CallError error;
  if (!docall(L, 1, 1, &error, path)) {
    lua_settop(L, 0);
    return {failed_status(ctx, error.message), {}};
  }
  sweep::PointResult r;
  try {
    if (!lua_isnil(L, -1)) {
      if (!lua_istable(L, -1))
        throw std::runtime_error(std::string("run(p) returned a ") + type_name(L, -1) +
                                 ": a table of figures (or nothing) expected");
      flatten(L, -1, "", r.figures, 0);
    }
  } catch (const std::runtime_error& e) {
    r = {sweep::error_status(path + ": " + e.what()), {}};
  }
  lua_settop(L, 0);
  return r;
}

sweep::PointResult run_script_point(Interpreter& lua, const std::string& script, const sweep::Point& p,
                                    const std::string& point_dir) {
  lua_State* L = lua.state();
  Context& ctx = lua.context();
  ctx.overrides.run.out_dir = point_dir, ctx.overrides.give("out");
  ctx.overrides.set.clear();
  for (const auto& [name, v] : p.params) {
    ScriptArg a;
    a.key = name;
    a.text = sweep::value_text(v);
    std::visit([&](const auto& x) { a.value = x; }, v);
    ctx.overrides.set.push_back(std::move(a));
  }
  ctx.divergence.reset();
  lua_pushnil(L);
  lua_setfield(L, LUA_REGISTRYINDEX, kLastRun);
  try {
    lua.run_file(script, 1);
  } catch (const ScriptError& e) {
    return {failed_status(ctx, e.what()), {}};
  }
  const bool sweep_file = luaL_testudata(L, -1, kSweepMeta) != nullptr;
  lua_settop(L, 0);
  if (sweep_file)
    return {sweep::error_status(script + " is a sweep file (it returns beltsim.sweep{...}): the --set lists of "
                                         "`beltsim sweep` are for ordinary scripts"),
            {}};
  std::string unread;
  for (const std::string& m : lua.unread_args(script)) unread += (unread.empty() ? "" : "; ") + m;
  if (!unread.empty()) return {sweep::error_status(unread), {}};
  sweep::PointResult r;
  if (lua_getfield(L, LUA_REGISTRYINDEX, kLastRun) == LUA_TTABLE) flatten(L, -1, "", r.figures, 0);
  lua_settop(L, 0);
  return r;
}

}  // namespace beltsim::script
