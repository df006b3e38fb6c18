// A scenario script's files in the sandbox (private to src/script; sandbox.hpp says which): where
// a path a script names lies in the sandbox's folders, and io.open, io.lines, io.input,
// io.output, loadfile, dofile and require, which open it there with the one routine of
// io/beneath.hpp, so that the check and the open are one operation.
#pragma once

#include <string>

struct lua_State;

namespace beltsim::script {

struct Context;

inline constexpr const char* kHow = "beltsim --trusted allows it (docs/limits-and-safety.md)";

// what a path written names, for the folders another beltsim holds (held_on_the_way): a file (the
// folders on the way to it), a folder files are written in (it too), a run's output folder (none:
// the run's own lock names who holds it)
enum class Written { kFile, kFolder, kRunFolder };

// "" when the sandbox lets a script read (or write) path, else why not, as
// "WHAT: reading|writing 'path' is not allowed in a scenario script (the sandbox: ...); --trusted";
// outputs: the path is one beltsim writes for the script (allowed under the script's folder too),
// and a symbolic link already on its way beneath the folder is refused; a write into a folder
// another beltsim process holds is refused
std::string path_refusal(const Context& c, const std::string& what, const std::string& path, bool write, bool outputs,
                         Written written = Written::kFile);

// the file functions of io (the io table on the stack top) and the global loadfile, dofile and
// require replaced by ones that open their files in the sandbox
void open_sandbox_files(lua_State* L, Context* ctx);

// "attempt to load a binary chunk (mode is 't')" at idx said plainly
void explain_binary(lua_State* L, int idx, const char* what);
// raises unless a load mode (nullptr: none given) allows text
void check_text_mode(lua_State* L, const char* mode, const char* what);

}  // namespace beltsim::script
