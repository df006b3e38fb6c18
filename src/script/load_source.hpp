// Lua source loaded from a file, as luaL_loadfile loads it, for every script file beltsim runs: the
// scenario, and what it loads with dofile, loadfile and require.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

struct lua_State;

namespace beltsim::script {

// the text of f loaded as a chunk named chunkname ("@path" or "=name"): a UTF-8 byte order mark and
// a first line starting with '#' skipped, keeping the line numbers; text only, never a precompiled
// chunk. Returns lua_load's status with the function or the message on the stack. Every message
// names the file and line: Lua's parser reports running out of C levels (a script nested more than
// 200 deep) as a bare "C stack overflow", which gets the line the parser had reached.
// When loaded is given, a file's chunk ("@path") loaded without error is added to it (once): its
// absolute path and the SHA-256 of all its bytes, what a sweep point records of the files that
// define it (sweep/inputs.hpp).
struct LoadedFile {
  std::string path, sha256;
};
int load_source(lua_State* L, std::FILE* f, const std::string& chunkname, std::vector<LoadedFile>* loaded = nullptr);

}  // namespace beltsim::script
