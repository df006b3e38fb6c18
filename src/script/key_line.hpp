// The line where a script wrote a table's key, so that an error about a value given in a
// multi-line table constructor names that value's line, not the line of the call:
//
//   5  local drive = beltsim.scene {
//   ...
//   22     mass_per_length = -1,
//
//   "paper_dry.lua:22: belt.mass_per_length must be > 0 (got -1 kg/m)"
//
// Lua keeps no line per table field, so the script's text is read: the first table constructor
// that opens on the call's line is scanned (comments, strings and function bodies skipped), and
// each `key =` in it is kept with its line and the tables around it (their keys, list positions
// and `name` fields). The path an error names matches a key when the tables around the key are
// the path's: "belt.sde.k" a `k` in an `sde` table in a `belt` table; "pulley 'idler'.tensioner.
// stiffness" a `stiffness` in a `tensioner` table in the table whose name is "idler";
// "friction.segments[2].mu" (or "friction.segments.2.mu") a `mu` in the second list entry of
// `segments` in `friction`. A leading "scene" or "run" names the call's own table. A path that
// names a table, not a key, is found at the line its constructor opens on: a list entry
// ("pulleys[2]", "friction.segments[2]") or a pulley ("pulley 'idler'", the table whose name it
// is); so is a key that such a table does not hold as written ("pulley 2.name" left out,
// "pulley 'idler'.centre" written as `center`). When nothing or more than one thing matches (a
// value built elsewhere, in a loop, or a call nested in another constructor), there is no answer
// and the call's line stays.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/key_path.hpp"

namespace beltsim::script {

using beltsim::KeyPath;  // (scene/key_path.hpp)

// the path at the start of an error message, or an empty chain when it names none:
//   "belt.mass_per_length must be > 0 (got -1 kg/m)"  -> belt.mass_per_length
//   "pulley 'driver' inertia must be > 0 (...)"        -> pulley 'driver', inertia
//   "unknown key 'radus' in pulley 'driver' (did ...)" -> pulley 'driver', radus
//   "run.frames.fps must be > 0 (...)"                 -> run.frames.fps
//   "friction.segments[2]: from and to are required"   -> friction.segments[2] (a list entry)
KeyPath message_path(std::string_view message);

// the line (from 1) of the one key (or list entry, or pulley's table) matching `path` in the table
// constructor that opens on `call_line` of `text`, or nothing (see above)
std::optional<int> key_line(std::string_view text, int call_line, const KeyPath& path);

// key_line for the script file `file` (a regular file of at most 4 MB; nothing otherwise)
std::optional<int> key_line_in_file(const std::string& file, int call_line, const KeyPath& path);

}  // namespace beltsim::script
