#include "script/load_source.hpp"

#include <cstring>
#include <filesystem>
#include <string_view>

#include "io/sha256.hpp"
#include "lua.h"

namespace beltsim::script {

namespace {

// lua_load's reader: first the characters read ahead, then the file a line at a time, so that the
// line the parser has reached is known when it fails without saying
struct Reader {
  std::FILE* f;
  Sha256* hash;  // of every byte read from f (nullptr: none kept)
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
  } else {
    // a line (or a buffer's worth) as it is, NULs included
    size_t n = 0;
    for (int c; n < sizeof r->buf && (c = std::getc(r->f)) != EOF;) {
      r->buf[n++] = static_cast<char>(c);
      if (c == '\n') break;
    }
    if (n == 0) return nullptr;
    if (r->hash) r->hash->update(r->buf, n);
    *size = n;
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

int load_source(lua_State* L, std::FILE* f, const std::string& chunkname, std::vector<LoadedFile>* loaded) {
  const bool record = loaded && chunkname.size() > 1 && chunkname[0] == '@';
  Sha256 hash;
  Reader r{f, record ? &hash : nullptr, "", 0, false, {}};
  // the bytes before the first one handed to the parser, each into the hash as it is read
  const auto get = [&] {
    const int c = std::getc(f);
    if (c != EOF && record) {
      const char b = static_cast<char>(c);
      hash.update(&b, 1);
    }
    return c;
  };
  int c = get();
  if (c == 0xEF && get() == 0xBB && get() == 0xBF) c = get();
  if (c == '#') {
    while (c != EOF && c != '\n') c = get();
    r.ahead = "\n";
    c = get();
  }
  if (c != EOF) r.ahead += static_cast<char>(c);
  const int status = lua_load(L, read_chunk, &r, chunkname.c_str(), "t");
  if (status == LUA_OK && record) {
    // what the parser left unread (nothing, after a whole chunk) counts too: the file's hash
    while (get() != EOF) continue;
    if (!std::ferror(f)) {
      std::error_code ec;
      const std::filesystem::path abs = std::filesystem::absolute(chunkname.substr(1), ec);
      LoadedFile lf{ec ? chunkname.substr(1) : abs.lexically_normal().string(), hash.hex()};
      bool known = false;
      for (const LoadedFile& x : *loaded) known = known || (x.path == lf.path && x.sha256 == lf.sha256);
      if (!known) loaded->push_back(std::move(lf));
    }
  }
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
