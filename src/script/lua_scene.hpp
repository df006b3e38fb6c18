// Lua bindings of the scene: beltsim.scene{...} and the scene's methods (info, element_near,
// run, start), the laws' helpers (beltsim.rpm, beltsim.ramp) and the run settings that run and
// start share (one table of keys and readers). The C++ classes know nothing of Lua.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "script/lua_check.hpp"
#include "sim/simulation.hpp"

namespace beltsim::script {

struct Context;

// the element's site as the table belt.mu functions get
void push_site(lua_State* L, const ElementSite& e);
// μ of each element from the value at mu_idx (a number or function(site)), on the elements whose
// start position s lies in [from, to] (wrapping round when from > to; every element without
// them); NaN for the others. Checks the range and every value (>= 0, finite).
std::vector<double> mu_over(lua_State* L, int mu_idx, const Scene& sc, std::optional<double> from,
                            std::optional<double> to, const std::string& what);
// frames = {...} (or the keys of sim:show, where `extra` lists keys read elsewhere)
FrameSettings to_frames(lua_State* L, int idx, const std::string& where, const std::vector<std::string>& extra = {});
// the scene at idx (method: for the message when it is not one)
const Scene* check_scene(lua_State* L, int idx, const char* method);
// the settings of scene:run{} (batch) or scene:start{} (live), command-line overrides applied
RunSettings read_run_settings(lua_State* L, int idx, const Scene& sc, Context* ctx, bool batch, bool* progress);

// adds `scene`, `rpm`, the laws' helpers (lua_law.hpp), `integrators` to the table on the top of
// the stack
void open_scene(lua_State* L, Context* ctx);

}  // namespace beltsim::script
