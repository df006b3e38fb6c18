// One sweep point run in an interpreter (sweep_run.hpp).
#include "script/sweep_run.hpp"

#include <variant>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/limits.hpp"
#include "script/lua_check.hpp"
#include "script/lua_sweep.hpp"
#include "sweep/results.hpp"

namespace beltsim::script {

namespace {

constexpr const char* kLoadedSweep = "beltsim.loaded_sweep";  // registry: the sweep load_sweep read

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

// p of run(p): an empty table whose metatable hands out the point's parameters (upvalue 1, a
// table NAME -> value) and notes each name read (upvalue 2, NAME -> true); upvalue 3 lists the
// names. A name the point does not have is an error, not a nil that the scene would take for its
// default (a misspelt p.pretension); pairs(p) lists them all, each counted as read. A key set by
// run(p) itself (p.extra = 1) is kept with the values and read back.
int l_point_index(lua_State* L) {
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) {
    lua_pushvalue(L, 2);
    lua_pushboolean(L, 1);
    lua_rawset(L, lua_upvalueindex(2));
    return 1;
  }
  std::vector<std::string> names;
  for (lua_Integer k = 1; lua_rawgeti(L, lua_upvalueindex(3), k) == LUA_TSTRING; ++k, lua_pop(L, 1))
    names.emplace_back(lua_tostring(L, -1));
  const bool text = lua_type(L, 2) == LUA_TSTRING;
  const std::string key = text ? lua_tostring(L, 2) : luaL_tolstring(L, 2, nullptr);
  // (the line of the read: fail() would look for a key of that name in a table around it)
  return luaL_error(
      L, "%s",
      ((text ? "p." + key : "p[" + key + "]") + ": the point has no parameter " + (text ? "'" + key + "'" : key) +
       (text ? did_you_mean(key, names) : "") + "; its parameters: " + join(names))
          .c_str());
}

int l_point_newindex(lua_State* L) {
  lua_settop(L, 3);
  lua_rawset(L, lua_upvalueindex(1));
  return 0;
}

int l_point_next(lua_State* L) {
  lua_settop(L, 2);
  return lua_next(L, 1) ? 2 : (lua_pushnil(L), 1);
}

int l_point_pairs(lua_State* L) {
  lua_pushnil(L);
  while (lua_next(L, lua_upvalueindex(1))) {
    lua_pop(L, 1);
    lua_pushvalue(L, -1);
    lua_pushboolean(L, 1);
    lua_rawset(L, lua_upvalueindex(2));
  }
  lua_pushcfunction(L, l_point_next);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushnil(L);
  return 3;
}

// pushes p for run(p) and, below it, the table of the names it reads (point_unread)
void push_point(lua_State* L, const sweep::Point& p) {
  lua_newtable(L);  // the names read
  const int read = lua_gettop(L);
  lua_createtable(L, 0, static_cast<int>(p.params.size()));
  const int values = lua_gettop(L);
  for (const auto& [name, v] : p.params) push_value(L, v), lua_setfield(L, values, name.c_str());
  lua_createtable(L, static_cast<int>(p.params.size()), 0);
  const int names = lua_gettop(L);
  lua_Integer k = 0;
  for (const auto& [name, v] : p.params) lua_pushstring(L, name.c_str()), lua_rawseti(L, names, ++k);
  lua_newtable(L);           // p
  lua_createtable(L, 0, 4);  // its metatable
  for (auto [event, fn] : {std::pair<const char*, lua_CFunction>{"__index", l_point_index},
                           std::pair<const char*, lua_CFunction>{"__newindex", l_point_newindex},
                           std::pair<const char*, lua_CFunction>{"__pairs", l_point_pairs}}) {
    lua_pushvalue(L, values), lua_pushvalue(L, read), lua_pushvalue(L, names);
    lua_pushcclosure(L, fn, 3);
    lua_setfield(L, -2, event);
  }
  lua_pushliteral(L, "beltsim.point"), lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  lua_replace(L, values);  // read, p
  lua_settop(L, values);
}

// the parameters of p that run(p) never read (the table of names read at idx)
std::vector<std::string> point_unread(lua_State* L, int idx, const sweep::Point& p) {
  std::vector<std::string> unread;
  for (const auto& [name, v] : p.params) {
    if (lua_getfield(L, idx, name.c_str()) == LUA_TNIL) unread.push_back("p." + name);
    lua_pop(L, 1);
  }
  return unread;
}

// the point's parameters as the script's --set values (beltsim.args)
void set_point_args(Context& ctx, const sweep::Point& p) {
  ctx.overrides.set.clear();
  for (const auto& [name, v] : p.params) {
    ScriptArg a;
    a.key = name;
    a.text = sweep::value_text(v);
    std::visit([&](const auto& x) { a.value = x; }, v);
    ctx.overrides.set.push_back(std::move(a));
  }
}

// the status of a failed call: the run's divergence when that is what ended it, with the whole
// message (file:line, the cause, where the samples are) after its time, less the message's own
// "the run diverged at t = ... s: " (the time in full precision is before it)
std::string failed_status(const Context& ctx, const std::string& message) {
  if (!ctx.divergence || message.find(ctx.divergence->second) == std::string::npos) return sweep::error_status(message);
  std::string m = message;
  if (const std::size_t at = m.find("the run diverged at t = "); at != std::string::npos)
    if (const std::size_t end = m.find(" s: ", at); end != std::string::npos) m.erase(at, end + 4 - at);
  return "diverged at t = " + number_text(ctx.divergence->first) +
         " s: " + sweep::error_status(m).substr(std::string("error: ").size());
}

// the refusal of a sweep file given --set lists (WrongFileKind), whichever form of the command
std::string sweep_file_given_set_lists(const std::string& script) {
  return script + " is a sweep file (it returns beltsim.sweep{...}): its points are its grid or samples; --set " +
         "lists are for an ordinary script (the quick form): run `beltsim sweep " + script + "` without them";
}

}  // namespace

std::vector<sweep::Point> load_sweep(Interpreter& lua, const std::string& path) {
  lua_State* L = lua.state();
  const std::string quick = "for a study of an ordinary script, give its parameters as --set lists: beltsim sweep " +
                            path + " --set NAME=V1,V2,..";
  // a simulation run as the file loads would run in every point's process as well, into out/<file>:
  // an ordinary script given without --set lists, which ran whole before it was refused
  Captured probe;
  probe.until_run = true;
  lua.set_capture(&probe);
  try {
    lua.run_file(path, 1);
  } catch (...) {
    lua.set_capture(nullptr);
    throw;
  }
  lua.set_capture(nullptr);
  if (!probe.run_at.empty()) {
    lua_settop(L, 0);
    throw WrongFileKind(probe.run_at + ": " + path + " runs a simulation as it loads: it is an ordinary script, " +
                        "not a sweep file (which returns beltsim.sweep{...} and runs its simulations in run(p)); " +
                        "nothing was run. For a study of it, give its parameters as --set lists: beltsim sweep " +
                        path + " --set NAME=V1,V2,..");
  }
  auto* box = static_cast<SweepBox*>(luaL_testudata(L, -1, kSweepMeta));
  if (!box) {
    const std::string got = type_name(L, -1);
    lua_settop(L, 0);
    throw ScriptError(path + ": a sweep file ends with `return beltsim.sweep{...}`; it returned " + got + " (" + quick +
                      ")");
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
  lua_Debug ar;  // where run is defined, for a result that is none
  lua_pushvalue(L, -1);
  const std::string where =
      lua_getinfo(L, ">S", &ar) && ar.linedefined > 0 ? path + ":" + std::to_string(ar.linedefined) : path;
  push_point(L, p);  // run, read, p
  lua_pushvalue(L, -2);
  lua_insert(L, -4);
  lua_remove(L, -2);  // read, run, p
  const int read = lua_gettop(L) - 2;
  CallError error;
  if (!docall(L, 1, 1, &error, path)) {
    lua_settop(L, 0);
    return {failed_status(ctx, error.message), {}};
  }
  sweep::PointResult r;
  try {
    // (a run(p) that forgot its return was ok with no figures)
    if (lua_isnil(L, -1)) {
      lua_settop(L, 0);
      return {sweep::error_status(where + ": run(p) returned nil; return a table of figures"), {}};
    }
    // a parameter that decided nothing: the points differ in its value and in nothing else
    if (const std::vector<std::string> unread = point_unread(L, read, p); !unread.empty())
      throw std::runtime_error(
          "run(p) never read " + join(unread) +
          (unread.size() == 1 ? ": a parameter that decides nothing makes points that differ in name only; read it in "
                                "run(p), or take it out of the sweep"
                              : ": parameters that decide nothing make points that differ in name only; read them in "
                                "run(p), or take them out of the sweep"));
    if (!lua_istable(L, -1))
      throw std::runtime_error(std::string("run(p) returned a ") + type_name(L, -1) + ": a table of figures expected");
    flatten(L, -1, "", r.figures, 0);
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
  set_point_args(ctx, p);
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
  // (a --point given by hand: the sweep that runs its points has refused the file already)
  if (sweep_file) throw WrongFileKind(sweep_file_given_set_lists(script));
  std::string unread;
  for (const std::string& m : lua.unread_args(script)) unread += (unread.empty() ? "" : "; ") + m;
  if (!unread.empty()) return {sweep::error_status(unread), {}};
  sweep::PointResult r;
  if (lua_getfield(L, LUA_REGISTRYINDEX, kLastRun) == LUA_TTABLE) flatten(L, -1, "", r.figures, 0);
  lua_settop(L, 0);
  return r;
}

void check_ordinary_script(Interpreter& lua, const std::string& script, const sweep::Point& p) {
  lua_State* L = lua.state();
  set_point_args(lua.context(), p);
  Captured probe;
  probe.until_run = probe.quiet = true;
  lua.set_capture(&probe);
  bool sweep_file = false;
  try {
    lua.run_file(script, 1);
    sweep_file = luaL_testudata(L, -1, kSweepMeta) != nullptr;
  } catch (const ScriptError&) {  // (its points say it)
  }
  lua_settop(L, 0);
  lua.set_capture(nullptr);
  lua.context().overrides.set.clear();
  if (sweep_file) throw WrongFileKind(sweep_file_given_set_lists(script));
}

}  // namespace beltsim::script
