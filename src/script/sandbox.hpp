// The Lua libraries a scenario script gets (private to src/script; docs/limits-and-safety.md).
//
// The sandbox: the base library with text-only loading (load, loadfile and dofile never load a
// precompiled chunk; string.dump is gone), string, table, math, utf8, coroutine; of os only time,
// clock, date, difftime and getenv; io whose files (io.open, io.lines, io.input, io.output, and
// dofile, loadfile) lie under the run's output folder (read and write) or the script's own folder
// (read only), opened from the folder without following any link or climbing out with `..`
// (sandbox_files.hpp); require of Lua files from the script's folder; debug.traceback;
// setmetatable without __gc (Lua runs finalisers with hooks off: no limit could stop one). Every other standard
// function (os.execute, io.popen, os.remove, os.exit, package.loadlib, debug.getinfo, ...) is
// kept as a function that raises "file:line: NAME is not allowed in a scenario script ...
// --trusted", so a script learns what it may not do and how to allow it.
#pragma once

#include <string>

#include "script/sandbox_files.hpp"  // Written
#include "sim/simulation.hpp"

struct lua_State;

namespace beltsim::script {

struct Context;

// the sandboxed libraries; the folders are read from ctx when a file is opened
void open_sandbox(lua_State* L, Context* ctx);

// The files beltsim itself writes or reads for a script (a run's out and frames paths, sim:save,
// sim:show{file}, sim:plot{file}; beltsim.resume reads) lie under the output folder or the
// script's folder, as for io.open, with no symbolic link on their way below the folder and, when
// written, no folder another beltsim holds on their way (checked here; beltsim's own writers then
// open them as any output, io/output_dir.hpp; a run locks its own folder). "" when allowed
// (always with --trusted), else the message:
// "WHAT: writing 'path' is not allowed in a scenario script (the sandbox: ...); beltsim --trusted
// allows it".
std::string output_refusal(const Context& c, const std::string& what, const std::string& path, bool write,
                           Written written = Written::kFile);
// the same for every path of a run's settings (out, frames.png, frames.video; relative frame
// paths are inside out), and, --trusted or not, an out that holds a sweep's study
// (sweep::study_folder_refusal) unless the run is captured; what: "run", "start", "resume"
std::string run_paths_refusal(const Context& c, const std::string& what, const RunSettings& rs);

}  // namespace beltsim::script
