// The run settings of scene:run{} and scene:start{} (lua_scene_run.hpp) read from their tables (one
// table of keys and readers), and the readers of μ, wet stretches and frames that the live
// simulation's methods (lua_sim.hpp) use too. The C++ classes know nothing of Lua.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "script/lua_check.hpp"
#include "sim/simulation.hpp"

namespace beltsim::script {

struct Context;

// a stretch [from, to] of the belt: both or neither given, each in [0, the belt's length]; "" or
// the problem's reason, with the key it is about (`what`, or what.from / what.to) in *key
// (check_range: a Lua error on that key)
std::string range_problem(const Scene& sc, std::optional<double> from, std::optional<double> to,
                          const std::string& what, std::string* key = nullptr);
void check_range(lua_State* L, const Scene& sc, std::optional<double> from, std::optional<double> to,
                 const std::string& what);
// μ of each element from the value at mu_idx (a number or function(site)), on the elements whose
// start position s lies in [from, to] (wrapping round when from > to; every element without
// them); NaN for the others. Checks the range and every value (>= 0, finite).
std::vector<double> mu_over(lua_State* L, int mu_idx, const Scene& sc, std::optional<double> from,
                            std::optional<double> to, const std::string& what);
// the element's start position s lies in [from, to] (wrapping round when from > to)
bool in_stretch(const ElementSite& site, double from, double to);
// the text of a wet stretch in events.csv ("mu = 0.2 on s in [0.1, 0.3] m"; mu absent: a function)
std::string wet_text(std::optional<double> mu, std::optional<double> from, std::optional<double> to,
                     std::optional<double> transition);
// whether setting μ (NaN: unchanged) changes any element's from `before`
bool changes_mu(const std::vector<double>& before, const std::vector<double>& mu);
// what a change of μ did, in one line (sim:wet, sim:set_mu and the live view's wet say it): how many
// elements' μ changed (mu: the new μ, NaN where unchanged; before: every element's μ before), where
// they are now (in contact with which pulley, or free), their μ before -> after; or, when none
// changed, that the elements addressed already had that μ. Reads the elements' contacts (a Lua
// law may throw)
std::string mu_change_text(Simulation& s, const std::vector<double>& before, const std::vector<double>& mu,
                           const std::string& what);
// The share of the wet μ an element at belt coordinate s takes with a transition of length tau
// [m] about each end of [from, to] (wrapping round the belt of length len when from > to): 1 inside
// farther than tau/2 from both ends, 0 outside farther than tau/2, linear across the ends; tau = 0
// is the sharp boundary (the ends inside). A stretch of the whole loop (from 0 to len) has no end:
// 1 everywhere.
double wet_share(double s, double from, double to, double len, double tau);
// wet_share of every element (by index) at its start position
std::vector<double> wet_shares(const Scene& sc, double from, double to, double tau);
// a transition longer than the stretch [from, to] (wrapping) leaves no element at the new μ: refused
// naming `what`.transition, the stretch's length and the value
void check_transition(lua_State* L, const Scene& sc, double from, double to, double tau, const std::string& what);
// the transition = tau [m] of a wet stretch's table at idx (sim:wet, run.events): absent, or >= 0
// and finite with the stretch's from and to
std::optional<double> read_transition(lua_State* L, int idx, bool has_range, const std::string& what);
// frames = {...} (or the keys of sim:show, where `extra` lists keys read elsewhere); times_only: neither
// png nor video needed (the times of kept states)
FrameSettings to_frames(lua_State* L, int idx, const std::string& where, const std::vector<std::string>& extra = {},
                        bool times_only = false);
// the settings of scene:run{} (batch) or scene:start{} (live), command-line overrides applied
RunSettings read_run_settings(lua_State* L, int idx, const Scene& sc, Context* ctx, bool batch, bool* progress);

// "stopped at its wall-time limit (max_wall = LIMIT s, or --max-wall LIMIT s where option: the
// command line gave it) at t = T s of TARGET s; the outputs up to
// then are in DIR": a run's or a live simulation's call's message, after the caller's name
std::string wall_limit_text(double limit, double t, double target, const std::string& outputs, bool option);
// " (the samples up to then are in DIR/timeseries.csv)": what a run's divergence ends with, in
// scene:run and in a live simulation's sim:run_to and sim:advance alike
std::string samples_note(const std::string& out_dir);

// the key of an output folder in Context::run_dirs (absolute, normalised, no trailing /), and its
// record once a run's outputs have opened there (scene:run, scene:start)
std::string run_dir_key(const std::string& out_dir);
void record_run_dir(Context* ctx, const std::string& out_dir);

// with Captured::until_run: ends the script at this call (scene:run, scene:start,
// beltsim.resume), noting where; nothing otherwise
void end_if_probing(lua_State* L, Context* ctx, const char* call);

// a capture of a scene:run{} (beltsim wp, beltsim modes) met a live simulation (scene:start,
// beltsim.resume): an error at this call's file:line, before anything runs or is written
void refuse_if_capturing(lua_State* L, Context* ctx, const char* call);

// After Ctrl-C or SIGTERM stopped a run, the script may go on to save or report what it has, but
// no run starts or goes on (scene:run, scene:start, beltsim.resume, sim:run_to, sim:advance): an
// error before any output is opened, so a later run cannot replace a folder with the one row of
// a run stopped at its start. The console clears the stop after each command.
void end_if_stopped(lua_State* L, const Context* ctx, const char* call);

// beltsim.stop_at([t])
int l_stop_at(lua_State* L);

// the metatable's name (its __name) of a table push_check pushes
inline constexpr const char* kCheckTable = "beltsim.check";
// pushes a checked run's estimate (sim/run_check.hpp) as { speed, tension, limit_speed,
// limit_tension, over, near, steps_ratio, shared, warned_t, failed }, with kCheckTable's metatable
void push_check(lua_State* L, const CheckEstimate& c);

}  // namespace beltsim::script
