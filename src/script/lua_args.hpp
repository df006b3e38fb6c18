// beltsim.args: the script parameters of the command line (--set KEY=VALUE, script_args.hpp) as
// the script reads them, and the keys it has not read.
#pragma once

#include <string>
#include <vector>

struct lua_State;

namespace beltsim::script {

struct Context;

// pushes the table beltsim.args (read-only; every key read is noted in ctx->args_read)
void push_args(lua_State* L, Context* ctx);
// the --set keys the script has not read (beltsim.args.KEY) so far, one message each naming the
// key, a suggestion among the keys it read, and those keys
// (so_far: said at a run's start, "has not been read ... before this run")
// (live: at a live simulation's start, where --t-end is no option for t_end)
std::vector<std::string> unread_arg_messages(const Context& ctx, const std::string& script, bool so_far = false,
                                             bool live = false);
// at the start of a script's first run: a warning on stderr for each --set key not read so far
// (a long run is not wasted on a misspelt key; the error comes after the script)
// the first call that integrates (scene:run, scene:start) fails, before integrating, when a
// --set key has not been read by then (call names it in the message); in the console it warns
void check_unread_args(lua_State* L, Context& ctx, const char* call);

}  // namespace beltsim::script
