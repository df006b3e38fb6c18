#include "media/shared_library.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <string>

namespace beltsim {

void* open_shared_library(const char* soname, const char* debian_package) {
  void* library = dlopen(soname, RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* why = dlerror();
    throw std::runtime_error(std::string("cannot open ") + soname + " (" + (why ? why : "dlopen failed") +
                             "; Debian package " + debian_package + ")");
  }
  return library;
}

void* shared_library_symbol(void* library, const char* soname, const char* name) {
  void* symbol = dlsym(library, name);
  if (!symbol) throw std::runtime_error(std::string(soname) + " has no " + name);
  return symbol;
}

}  // namespace beltsim
