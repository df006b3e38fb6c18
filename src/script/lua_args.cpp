// beltsim.args, the script parameters of the command line (--set KEY=VALUE; docs/lua-api.md): an
// empty table whose metatable hands out the values and notes every key read, given or not. After
// the script, a --set key it never read is reported with the keys it did read (a misspelt --set is
// found that way, and a misspelt read shows as a nil the script sees).
#include "script/lua_args.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <type_traits>
#include <variant>

#include "io/suggest.hpp"
#include "script/context.hpp"
#include "script/lua_check.hpp"
#include "script/progress.hpp"
#include "sim/run_table.hpp"

namespace beltsim::script {

namespace {

Context& context_of(lua_State* L) {
  return *static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
}

// pushes the --set value of key (nil when not given) and notes the key as read
void push_arg(lua_State* L, Context& ctx, const std::string& key) {
  if (std::find(ctx.args_read.begin(), ctx.args_read.end(), key) == ctx.args_read.end()) ctx.args_read.push_back(key);
  for (const ScriptArg& a : ctx.overrides.set) {
    if (a.key != key) continue;
    std::visit(
        [L](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, long long>)
            lua_pushinteger(L, static_cast<lua_Integer>(v));
          else if constexpr (std::is_same_v<T, double>)
            lua_pushnumber(L, v);
          else if constexpr (std::is_same_v<T, bool>)
            lua_pushboolean(L, v);
          else
            lua_pushlstring(L, v.data(), v.size());
        },
        a.value);
    return;
  }
  lua_pushnil(L);
}

// beltsim.args.KEY
int l_args_index(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return lua_pushnil(L), 1;
  push_arg(L, context_of(L), lua_tostring(L, 2));
  return 1;
}

int l_args_newindex(lua_State* L) {
  fail(L, "beltsim.args is read-only: its values come from the command line (--set KEY=VALUE)");
}

// pairs(beltsim.args): every given key (each counts as read)
int l_args_next(lua_State* L) {
  Context& ctx = context_of(L);
  const auto& set = ctx.overrides.set;
  size_t k = 0;
  if (lua_type(L, 2) == LUA_TSTRING) {
    const std::string key = lua_tostring(L, 2);
    while (k < set.size() && set[k].key != key) ++k;
    ++k;
  }
  if (k >= set.size()) return lua_pushnil(L), 1;
  lua_pushstring(L, set[k].key.c_str());
  push_arg(L, ctx, set[k].key);
  return 2;
}
int l_args_pairs(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushcclosure(L, l_args_next, 1);
  lua_pushvalue(L, 1);
  lua_pushnil(L);
  return 3;
}

}  // namespace

void push_args(lua_State* L, Context* ctx) {
  lua_newtable(L);
  lua_createtable(L, 0, 4);
  for (auto [name, fn] : {std::pair<const char*, lua_CFunction>{"__index", l_args_index},
                          std::pair<const char*, lua_CFunction>{"__newindex", l_args_newindex},
                          std::pair<const char*, lua_CFunction>{"__pairs", l_args_pairs}}) {
    lua_pushlightuserdata(L, ctx);
    lua_pushcclosure(L, fn, 1);
    lua_setfield(L, -2, name);
  }
  lua_pushliteral(L, "beltsim.args"), lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
}

namespace {

// " (did you mean the option --rtol 1e-3?)" when `key` (t-end or t_end) names a run setting the
// command's own options override (a user gave --set rtol=1e-3 for --rtol 1e-3), "" otherwise; at
// a live simulation's start not t_end, which --t-end does not set for it (its run_to calls name
// its times: a user's trial followed the hint and the run still stopped at 0.2 s)
std::string option_meant(const Overrides& o, const ScriptArg& a, bool live) {
  std::string key = a.key;
  std::replace(key.begin(), key.end(), '-', '_');
  if (live && key == "t_end") return "";
  if (std::find(o.option_keys.begin(), o.option_keys.end(), key) == o.option_keys.end()) return "";
  const RunSetting* s = find_run_setting(key);
  // (a flag's false is its default: no option says it)
  if (!s || s->option.empty() || (s->kind == RunKind::flag && a.text != "true")) return "";
  const std::string option(s->option);
  return " (did you mean the option " + (s->kind == RunKind::flag ? option : option + " " + a.text) + "?)";
}

}  // namespace

std::vector<std::string> unread_arg_messages(const Context& ctx, const std::string& script, bool so_far, bool live) {
  std::vector<std::string> out;
  for (const ScriptArg& a : ctx.overrides.set) {
    if (std::find(ctx.args_read.begin(), ctx.args_read.end(), a.key) != ctx.args_read.end()) continue;
    std::string meant = option_meant(ctx.overrides, a, live);
    if (meant.empty()) meant = did_you_mean(a.key, ctx.args_read);
    out.push_back("--set " + a.key + "=" + a.text + (so_far ? " has not been read by " : " was never read by ") +
                  script + (so_far ? " before its first run or start" : "") + meant +
                  "; keys it read: " + (ctx.args_read.empty() ? std::string("none") : join(ctx.args_read)));
  }
  return out;
}

void check_unread_args(lua_State* L, Context& ctx, const char* call) {
  if (ctx.args_warned || ctx.capture) return;
  ctx.args_warned = true;
  const std::string script = ctx.script.empty() ? "the console" : ctx.script;
  std::string all;
  for (const std::string& m : unread_arg_messages(ctx, script, true, std::string(call) == "start")) {
    if (ctx.interactive) say("beltsim: warning: %s\n", m.c_str());
    all += (all.empty() ? "" : "; ") + m;
  }
  // (scene:start integrates nothing itself: its refusal says what it did not do)
  if (!all.empty() && !ctx.interactive)
    fail(L, std::string(call) +
                (std::string(call) == "start" ? ": the simulation was not started: " : ": nothing was integrated: ") +
                all);
}

}  // namespace beltsim::script
