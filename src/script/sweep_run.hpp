// One point of a sweep run in an interpreter (docs/sweeps.md): the sweep file's run(p), or an
// ordinary script with the point's parameters as --set values (the quick form of the command
// line). The sweep's points are read by the binding of beltsim.sweep (lua_sweep.hpp).
#pragma once

#include <string>
#include <vector>

#include "script/interpreter.hpp"
#include "sweep/points.hpp"
#include "sweep/results.hpp"

namespace beltsim::script {

// the file is not of the kind the command's form needs (bad usage): a sweep file given --set lists,
// an ordinary script without them
struct WrongFileKind : ScriptError {
  using ScriptError::ScriptError;
};

// runs the sweep file and returns its points; throws ScriptError ("file:line: why") when it fails
// or does not return beltsim.sweep{...}, WrongFileKind when it calls scene:run{}, scene:start{} or
// beltsim.resume as it loads (an ordinary script: the file ends there, nothing run)
std::vector<sweep::Point> load_sweep(Interpreter& lua, const std::string& path);

// run(p) of the sweep loaded last by load_sweep, its runs writing to point_dir unless they say
// otherwise. The result's figures are what run(p) returned (nested tables flattened with dots:
// omega.driver); an error gives an "error: ..." or "diverged at t = T s: ..." status. The caller checks
// lua.interrupted() and the stop signal: a stopped point is not a result.
sweep::PointResult run_sweep_point(Interpreter& lua, const std::string& path, const sweep::Point& p,
                                   const std::string& point_dir);

// the quick form: the script run with the point's parameters as its --set values and its runs'
// folder point_dir; the figures are the result table of its last scene:run{}. Throws
// WrongFileKind, nothing written, when the script is a sweep file (check_ordinary_script's error)
sweep::PointResult run_script_point(Interpreter& lua, const std::string& script, const sweep::Point& p,
                                    const std::string& point_dir);

// the quick form's script is an ordinary one: run with the point's --set values up to its first
// scene:run{}, scene:start{} or beltsim.resume (which it does not make: nothing integrated or
// written), it does not return beltsim.sweep{...}. Throws WrongFileKind when it does; an error of
// the script is left to its points to say, each with its own values.
void check_ordinary_script(Interpreter& lua, const std::string& script, const sweep::Point& p);

}  // namespace beltsim::script
