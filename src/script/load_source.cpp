#include "script/load_source.hpp"

#include <cstring>
#include <string_view>

#include "lua.h"

namespace beltsim::script {

namespace {

// lua_load's reader: first the characters read ahead, then the file a line at a time, so that the
// line the parser has reached is known when it fails without saying
struct Reader {
  std::FILE* f;
  std::string ahead;
  long newlines = 0;   // in the text handed out so far
  bool ended = false;  // the last piece handed out ends with a line feed
  char buf[BUFSIZ];
  // the line of the last character handed out (1-based)
  long line() const { return 1 + newlines - (ended ? 1 : 0); }
};

const char* read_chunk(lua_State*, void* ud, size_t* size) {
  auto* r = static_cast<Reader*>(ud);
  if (!r->ahead.empty()) {
    *size = r->ahead.size();
    std::memcpy(r->buf, r->ahead.data(), *size);
    r->ahead.clear();
  } else if (std::fgets(r->buf, sizeof r->buf, r->f)) {
    *size = std::strlen(r->buf);  // (a NUL inside a line ends the piece early; the rest follows)
  } else {
    return nullptr;
  }
  for (size_t i = 0; i < *size; ++i) r->newlines += r->buf[i] == '\n';
  r->ended = *size > 0 && r->buf[*size - 1] == '\n';
  return r->buf;
}

// the prefix Lua's messages give a chunk: "path:" for "@path", "name:" for "=name"
std::string source_prefix(const std::string& chunkname) {
  return (chunkname.empty() ? chunkname : chunkname.substr(1)) + ":";
}

}  // namespace

int load_source(lua_State* L, std::FILE* f, const std::string& chunkname) {
  Reader r{f, "", 0, false, {}};
  int c = std::getc(f);
  if (c == 0xEF && std::getc(f) == 0xBB && std::getc(f) == 0xBF) c = std::getc(f);
  if (c == '#') {
    while (c != EOF && c != '\n') c = std::getc(f);
    r.ahead = "\n";
    c = std::getc(f);
  }
  if (c != EOF) r.ahead += static_cast<char>(c);
  const int status = lua_load(L, read_chunk, &r, chunkname.c_str(), "t");
  if (std::ferror(f)) {
    lua_settop(L, lua_gettop(L) - 1);
    lua_pushfstring(L, "cannot read %s", chunkname.c_str() + 1);
    return LUA_ERRFILE;
  }
  if (status != LUA_OK && status != LUA_ERRMEM) {
    const char* msg = lua_tostring(L, -1);
    const std::string prefix = source_prefix(chunkname);
    if (msg && std::string_view(msg).substr(0, prefix.size()) != prefix) {
      const std::string bare = msg;
      lua_pop(L, 1);
      // (inside a running script the message handler in force has added a traceback to it)
      constexpr std::string_view kOverflow = "C stack overflow";
      const bool nesting = std::string_view(bare).substr(0, kOverflow.size()) == kOverflow;
      lua_pushfstring(L, "%s%d: %s", prefix.c_str(), static_cast<int>(r.line()),
                      nesting ? "C stack overflow (the script nests deeper than Lua's parser allows, 200 levels of "
                                "brackets, calls and blocks)"
                              : bare.c_str());
    }
  }
  return status;
}

}  // namespace beltsim::script
