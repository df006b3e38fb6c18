// A shared library opened when first needed (dlopen), not linked: FFmpeg's and Mesa's libraries
// pull in over a hundred others, whose loading took most of the start of a run that draws nothing
// (0.2 s of CPU of 0.25 s, 0.45 s under ASan). Opened once, never closed.
#pragma once

namespace beltsim {

// the library of that file name (a soname, as "libEGL.so.1"); throws std::runtime_error naming it,
// dlopen's reason and the Debian package that has it
void* open_shared_library(const char* soname, const char* debian_package);
// the symbol's address in a library open_shared_library opened; throws naming both when absent
void* shared_library_symbol(void* library, const char* soname, const char* name);

}  // namespace beltsim

// For a table of a library's functions written as an X-macro list: BELTSIM_SHARED_DECLARE(f) a
// member pointer of f's own type, BELTSIM_SHARED_LOAD(f) its address from `library`, whose file
// name is `soname` (both names in scope where the list is expanded)
#define BELTSIM_SHARED_DECLARE(name) decltype(&::name) name = nullptr;
#define BELTSIM_SHARED_LOAD(name) \
  name = reinterpret_cast<decltype(&::name)>(::beltsim::shared_library_symbol(library, soname, #name));
