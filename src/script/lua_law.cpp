// Pulley laws from Lua (see lua_law.hpp; the terms' formulas are at the top of model/laws.cpp).
//
//   law       = number | function(t, omega) | law table | { law, law, ... }   (a list: the sum)
//   law table = { constant, per_speed, table = {{t, v}, ...}, per_speed_table = {{omega, M}, ...},
//                 ramp = {t0, t1, from, to, shape}, step = {t, from, to},
//                 sine = {mean, amplitude, frequency, phase},
//                 mean_speed = ω_m, harmonics = {{order, amplitude, phase}, ...},
//                 law, law, ... }    (named terms and listed laws, all summed)
//
// A speed law's function is called as f(t); a torque law's as f(t, omega). Each call runs Lua
// (one per evaluation; the finite differences of its derivatives, model/laws.cpp, take more); a
// law without a function runs none while integrating.
#include "script/lua_law.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/limits.hpp"

namespace beltsim::script {

namespace {

// A Lua function as a law. Calls go through the main thread with the script's message handler;
// an error, a value that is not a number or one that is not finite is a LawError naming the
// function's place and the error's own file:line; its code interrupted by Ctrl-C, a StoppedInCode.
class LuaLaw final : public LawFunction {
 public:
  LuaLaw(lua_State* L, int idx, bool speed, std::string what, std::shared_ptr<LawHost> host)
      : host_(std::move(host)), speed_(speed), what_(std::move(what)) {
    where_ = function_place(L, idx);
    lua_pushvalue(L, idx);
    ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  }
  ~LuaLaw() override {
    if (host_->L) luaL_unref(host_->L, LUA_REGISTRYINDEX, ref_);
  }
  LuaLaw(const LuaLaw&) = delete;
  LuaLaw& operator=(const LuaLaw&) = delete;

  double value(double t, double omega) const override {
    lua_State* L = host_->L;
    if (!L) throw LawError(what_ + " (" + describe() + "): its Lua state is closed");
    calls_++;
    const int top = lua_gettop(L);
    if (!lua_checkstack(L, 4)) throw LawError(what_ + " (" + describe() + "): the Lua stack is full");
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref_);
    lua_pushnumber(L, t);
    if (!speed_) lua_pushnumber(L, omega);
    CallError e;
    std::string error;
    double v = 0;
    bool stopped = false;  // its code interrupted by Ctrl-C: the run stops (StoppedInCode)
    if (!docall(L, speed_ ? 1 : 2, 1, &e, where_)) {
      error = e.message;
      stopped = take_interrupt(L);
    } else if (lua_type(L, -1) != LUA_TNUMBER) {
      error = std::string("it returned ") + luaL_typename(L, -1) + ", a number expected";
    } else {
      v = lua_tonumber(L, -1);
      if (!std::isfinite(v)) error = "it returned " + rounded_text(v) + ", a finite number expected";
    }
    lua_settop(L, top);
    if (!error.empty()) {
      std::string m = what_ + " (" + describe() + ") at t = " + rounded_text(t) + " s";
      if (!speed_) m += ", omega = " + rounded_text(omega) + " rad/s";
      if (stopped) throw StoppedInCode(m + ": " + error);
      throw LawError(m + ": " + error);
    }
    return v;
  }
  std::string describe() const override { return "function at " + where_; }
  long calls() const override { return calls_; }

 private:
  std::shared_ptr<LawHost> host_;
  bool speed_;
  std::string what_, where_;
  int ref_ = LUA_NOREF;
  mutable long calls_ = 0;
};

const std::vector<std::string> kLawKeys{"constant", "per_speed", "table", "per_speed_table", "ramp",
                                        "step",     "sine",      "mean_speed", "harmonics"};

double number_at(lua_State* L, int t, lua_Integer k, const std::string& what) {
  lua_rawgeti(L, t, k);
  const double v = to_number(L, -1, what);
  lua_pop(L, 1);
  return v;
}

// {{x, y}, ...}: at least one pair
void read_pairs(lua_State* L, int idx, const std::string& what, const char* pair, std::vector<double>& x,
                std::vector<double>& y) {
  require_table(L, idx, what);
  check_sequence(L, idx, what);
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  if (n < 1) fail_on(L, what, std::string("at least one ") + pair + " pair expected");
  for (lua_Integer k = 1; k <= n; ++k) {
    const std::string w = what + " entry " + std::to_string(k) + " (" + pair + ")";
    lua_rawgeti(L, idx, k);
    if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2)
      fail_on(L, w, std::string("two numbers expected, got ") + type_name(L, -1));
    x.push_back(number_at(L, lua_gettop(L), 1, w));
    y.push_back(number_at(L, lua_gettop(L), 2, w));
    lua_pop(L, 1);
  }
}

double required(lua_State* L, int t, const char* key, const std::string& what) {
  const auto v = opt_number(L, t, key, what);
  if (!v) fail(L, what + "." + key + " is required");
  return *v;
}

Ramp read_ramp(lua_State* L, int idx, const std::string& what) {
  require_table(L, idx, what);
  check_keys(L, idx, what, {"t0", "t1", "from", "to", "shape"});
  Ramp r;
  r.t0 = opt_number(L, idx, "t0", what).value_or(0.0);
  r.t1 = required(L, idx, "t1", what);
  r.from = opt_number(L, idx, "from", what).value_or(0.0);
  r.to = required(L, idx, "to", what);
  if (const auto k = opt_choice(L, idx, "shape", what, {"linear", "cosine"})) r.cosine = *k == 1;
  if (!(r.t1 > r.t0)) {
    std::ostringstream m;
    m << what << ": t1 must be > t0 (got t0 = " << r.t0 << " s, t1 = " << r.t1 << " s; a jump is beltsim.step)";
    fail(L, m.str());
  }
  return r;
}

Ramp read_step(lua_State* L, int idx, const std::string& what) {
  require_table(L, idx, what);
  check_keys(L, idx, what, {"t", "from", "to"});
  Ramp r;
  r.t0 = r.t1 = required(L, idx, "t", what);
  r.from = opt_number(L, idx, "from", what).value_or(0.0);
  r.to = required(L, idx, "to", what);
  return r;
}

Sine read_sine(lua_State* L, int idx, const std::string& what) {
  require_table(L, idx, what);
  check_keys(L, idx, what, {"mean", "amplitude", "frequency", "phase"});
  Sine s;
  s.mean = opt_number(L, idx, "mean", what).value_or(0.0);
  s.amplitude = required(L, idx, "amplitude", what);
  s.frequency = required(L, idx, "frequency", what);
  s.phase = opt_number(L, idx, "phase", what).value_or(0.0);
  return s;
}

void read_harmonics(lua_State* L, int idx, const std::string& what, double mean_speed, std::vector<Harmonic>& out) {
  require_table(L, idx, what);
  check_sequence(L, idx, what);
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  if (n < 1) fail_on(L, what, "at least one {order, amplitude, phase} expected");
  for (lua_Integer k = 1; k <= n; ++k) {
    const std::string w = what + " entry " + std::to_string(k) + " ({order, amplitude, phase})";
    lua_rawgeti(L, idx, k);
    const int e = lua_gettop(L);
    if (!lua_istable(L, e) || lua_rawlen(L, e) < 2 || lua_rawlen(L, e) > 3)
      fail_on(L, w, std::string("two or three numbers expected, got ") + type_name(L, e));
    Harmonic h;
    h.order = number_at(L, e, 1, w);
    h.amplitude = number_at(L, e, 2, w);
    h.phase = lua_rawlen(L, e) == 3 ? number_at(L, e, 3, w) : 0.0;
    h.mean_speed = mean_speed;
    out.push_back(h);
    lua_pop(L, 1);
  }
}

constexpr int kMaxDepth = 16;

// adds the law at idx to `law`
void add_law(lua_State* L, int idx, const std::string& what, bool speed, Context* ctx, TimeSpeedLaw& law, int depth) {
  idx = lua_absindex(L, idx);
  if (depth > kMaxDepth)
    fail_on(L, what,
            std::string("laws nested deeper than ") + std::to_string(kMaxDepth) + " (a table that holds itself?)");
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER:
      law.constant += lua_tonumber(L, idx);
      return;
    case LUA_TFUNCTION: {
      TimeSpeedLaw f;
      f.fn = std::make_shared<LuaLaw>(L, idx, speed, what, ctx->law_host);
      law += f;
      return;
    }
    case LUA_TTABLE:
      break;
    default:
      fail_on(L, what,
              std::string("a number, a law table or function(t") + (speed ? ")" : ", omega)") + " expected, got " +
                  type_name(L, idx));
  }
  // the keys: named terms, and a list of laws 1..n
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) {
      const std::string key = lua_tostring(L, -1);
      if (std::find(kLawKeys.begin(), kLawKeys.end(), key) == kLawKeys.end())
        fail(L, "unknown key '" + key + "' in " + what + did_you_mean(key, kLawKeys) + "; valid keys: " + join(kLawKeys) +
                    ", and laws as a list (summed)");
    } else if (!lua_isinteger(L, -1) || lua_tointeger(L, -1) < 1 || lua_tointeger(L, -1) > n) {
      fail_on(L, what, "named terms and a list of laws without holes expected");
    }
  }
  TimeSpeedLaw own;
  own.constant = opt_number(L, idx, "constant", what).value_or(0.0);
  own.per_speed = opt_number(L, idx, "per_speed", what).value_or(0.0);
  if (field(L, idx, "table")) read_pairs(L, lua_gettop(L), what + ".table", "{t, value}", own.t, own.value), lua_pop(L, 1);
  if (field(L, idx, "per_speed_table"))
    read_pairs(L, lua_gettop(L), what + ".per_speed_table", "{omega, value}", own.omega, own.omega_value), lua_pop(L, 1);
  if (field(L, idx, "ramp")) own.ramps.push_back(read_ramp(L, lua_gettop(L), what + ".ramp")), lua_pop(L, 1);
  if (field(L, idx, "step")) own.ramps.push_back(read_step(L, lua_gettop(L), what + ".step")), lua_pop(L, 1);
  if (field(L, idx, "sine")) own.sines.push_back(read_sine(L, lua_gettop(L), what + ".sine")), lua_pop(L, 1);
  const auto mean_speed = opt_number(L, idx, "mean_speed", what);
  if (field(L, idx, "harmonics")) {
    if (!mean_speed) fail_on(L, what + ".harmonics", "mean_speed [rad/s] is required beside it (the orders are of it)");
    read_harmonics(L, lua_gettop(L), what + ".harmonics", *mean_speed, own.harmonics);
    lua_pop(L, 1);
  } else if (mean_speed) {
    fail_on(L, what + ".mean_speed", "only for harmonics (the orders' speed), and no harmonics are given");
  }
  // a table's own check first, so that its errors name its own key
  std::string error;
  KeyPath about;
  try {
    validate_law(what, own, speed);
  } catch (const ParameterError& e) {
    error = e.what(), about = e.path;
  }
  if (!error.empty()) fail_at(L, about, error);
  law += own;
  for (lua_Integer k = 1; k <= n; ++k) {
    lua_rawgeti(L, idx, k);
    add_law(L, -1, what + " entry " + std::to_string(k), speed, ctx, law, depth + 1);
    lua_pop(L, 1);
  }
}

// pushes { <key> = <the table at idx> } (a helper's result: a law table of one term)
int wrap(lua_State* L, const char* key, int idx) {
  idx = lua_absindex(L, idx);
  lua_createtable(L, 0, 1);
  lua_pushvalue(L, idx);
  lua_setfield(L, -2, key);
  return 1;
}

// the helper's law on the top of the stack ({ <term> = {...} }), checked for what its use does not
// change; errors name the helper ("beltsim.ramp.t1"). Its values are checked, in the unit of its use
// (N·m or rad/s), when it is given to a key (add_law)
void check_helper(lua_State* L, const std::string& term) {
  const std::string what = "beltsim." + term;
  TimeSpeedLaw law;
  lua_getfield(L, -1, term.c_str());
  const int t = lua_gettop(L);
  if (term == "ramp") law.ramps.push_back(read_ramp(L, t, what));
  if (term == "step") law.ramps.push_back(read_step(L, t, what));
  if (term == "sine") law.sines.push_back(read_sine(L, t, what));
  lua_pop(L, 1);
  std::string error;
  KeyPath about;
  try {
    validate_helper_law(what, law);
  } catch (const ParameterError& e) {
    error = e.what(), about = e.path;
  }
  if (!error.empty()) fail_at(L, about, error);
}

// beltsim.ramp{ t0 = 0, t1, from = 0, to, shape = "linear" | "cosine" } or beltsim.ramp(t1, to)
// (from 0 at t = 0) -> { ramp = {...} }
int l_ramp(lua_State* L) {
  if (lua_type(L, 1) == LUA_TTABLE) {
    check_args(L, "beltsim.ramp", {{"{t0, t1, from, to, shape}", kTable}});
    lua_createtable(L, 0, 5);
    const int r = lua_gettop(L);
    check_keys(L, 1, "beltsim.ramp", {"t0", "t1", "from", "to", "shape"});
    for (const char* k : {"t0", "t1", "from", "to", "shape"}) lua_getfield(L, 1, k), lua_setfield(L, r, k);
  } else {
    check_args(L, "beltsim.ramp", {{"t1", kNumber}, {"to", kNumber}});
    lua_createtable(L, 0, 4);
    set_number(L, "t0", 0.0);
    set_number(L, "t1", lua_tonumber(L, 1));
    set_number(L, "from", 0.0);
    set_number(L, "to", lua_tonumber(L, 2));
  }
  wrap(L, "ramp", -1);
  check_helper(L, "ramp");
  return 1;
}

// beltsim.step{ t, from = 0, to } (the law key's form, as beltsim.ramp takes both: a user's
// beltsim.step{ t = 0.2, to = 13 } was refused, "expected 3 arguments") or beltsim.step(t, from, to)
// -> { step = {t, from, to} }
int l_step(lua_State* L) {
  if (lua_type(L, 1) == LUA_TTABLE) {
    check_args(L, "beltsim.step", {{"{t, from, to}", kTable}});
    lua_createtable(L, 0, 3);
    const int r = lua_gettop(L);
    check_keys(L, 1, "beltsim.step", {"t", "from", "to"});
    for (const char* k : {"t", "from", "to"}) lua_getfield(L, 1, k), lua_setfield(L, r, k);
  } else {
    check_args(L, "beltsim.step", {{"t", kNumber}, {"from", kNumber}, {"to", kNumber}});
    lua_createtable(L, 0, 3);
    set_number(L, "t", lua_tonumber(L, 1));
    set_number(L, "from", lua_tonumber(L, 2));
    set_number(L, "to", lua_tonumber(L, 3));
  }
  wrap(L, "step", -1);
  check_helper(L, "step");
  return 1;
}

// beltsim.sine{ mean = 0, amplitude, frequency [Hz], phase = 0 [rad] } -> { sine = {...} }
int l_sine(lua_State* L) {
  check_args(L, "beltsim.sine", {{"{mean, amplitude, frequency, phase}", kTable}});
  check_keys(L, 1, "beltsim.sine", {"mean", "amplitude", "frequency", "phase"});
  lua_createtable(L, 0, 4);
  const int s = lua_gettop(L);
  for (const char* k : {"mean", "amplitude", "frequency", "phase"}) lua_getfield(L, 1, k), lua_setfield(L, s, k);
  wrap(L, "sine", -1);
  check_helper(L, "sine");
  return 1;
}

}  // namespace

TimeSpeedLaw to_law(lua_State* L, int idx, const std::string& what, bool speed, Context* ctx) {
  TimeSpeedLaw law;
  add_law(L, idx, what, speed, ctx, law, 0);
  std::string error;
  KeyPath about;
  try {
    validate_law(what, law, speed);  // the sum: a speed table summed into a speed law, say
  } catch (const ParameterError& e) {
    error = e.what(), about = e.path;
  }
  if (!error.empty()) fail_at(L, about, error);
  return law;
}

void open_laws(lua_State* L) {
  lua_pushcfunction(L, l_ramp), lua_setfield(L, -2, "ramp");
  lua_pushcfunction(L, l_step), lua_setfield(L, -2, "step");
  lua_pushcfunction(L, l_sine), lua_setfield(L, -2, "sine");
}

}  // namespace beltsim::script
