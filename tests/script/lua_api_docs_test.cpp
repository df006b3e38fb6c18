// docs/lua-api.md against the API's own help table (script/lua_help.hpp, api_help(), which help()
// prints): every entry has a table row in the docs whose call is the entry's call, and every row
// of the docs that names a call of the API is an entry of the help table.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "lua.h"
#include "script/interpreter.hpp"
#include "script/lua_help.hpp"
#include "support/files.hpp"

namespace fs = std::filesystem;
using beltsim::script::api_help;
using beltsim::script::HelpEntry;

namespace {

using beltsim::test::slurp;

// a help entry's call as the docs write it: what precedes " -> " (the docs give the result in
// the row's second column)
std::string call_of(const HelpEntry& h) {
  const std::string c = h.call;
  const auto arrow = c.find(" -> ");
  return arrow == std::string::npos ? c : c.substr(0, arrow);
}

// the first cell of a Markdown table row (cells split at pipes not escaped as \|), and the code
// spans in it with \| read as |
std::vector<std::string> first_cell_code(const std::string& row) {
  std::string cell;
  for (size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '\\' && i + 1 < row.size() && row[i + 1] == '|') {
      cell += '|', ++i;
      continue;
    }
    if (row[i] == '|') break;
    cell += row[i];
  }
  std::vector<std::string> spans;
  size_t at = 0;
  while ((at = cell.find('`', at)) != std::string::npos) {
    const size_t end = cell.find('`', at + 1);
    if (end == std::string::npos) break;
    spans.push_back(cell.substr(at + 1, end - at - 1));
    at = end + 1;
  }
  return spans;
}

bool names_a_call(const std::string& code) {
  for (const char* prefix : {"sim:", "sim.", "scene:", "beltsim.", "help("})
    if (code.rfind(prefix, 0) == 0) return true;
  return false;
}

// the calls of docs/lua-api.md's table rows, with their line numbers
std::multimap<std::string, int> documented_calls() {
  std::multimap<std::string, int> calls;
  std::istringstream docs(slurp(fs::path(BELTSIM_SOURCE_DIR) / "docs" / "lua-api.md"));
  std::string line;
  for (int n = 1; std::getline(docs, line); ++n) {
    if (line.rfind("| `", 0) != 0) continue;
    for (const std::string& code : first_cell_code(line))
      if (names_a_call(code)) calls.emplace(code, n);
  }
  return calls;
}

TEST(LuaApiDocs, EveryHelpEntryHasARowWithItsCall) {
  const auto docs = documented_calls();
  ASSERT_FALSE(docs.empty()) << "docs/lua-api.md has no table row of API calls";
  for (const HelpEntry& h : api_help())
    EXPECT_EQ(docs.count(call_of(h)), 1u)
        << "help entry '" << h.name << "': docs/lua-api.md needs exactly one table row whose first cell is `"
        << call_of(h) << "`";
}

TEST(LuaApiDocs, EveryRowIsAHelpEntry) {
  std::set<std::string> help;
  for (const HelpEntry& h : api_help()) help.insert(call_of(h));
  for (const auto& [call, line] : documented_calls())
    EXPECT_TRUE(help.count(call)) << "docs/lua-api.md:" << line << ": `" << call
                                  << "` is not a call of the help table (src/script/lua_sim.cpp, api_help())";
}

// what a script finds in the beltsim table is what help() and the docs describe: every key of it
// has a help entry of that name (help("version") once said nothing is called so)
TEST(LuaApiDocs, EveryKeyOfTheBeltsimTableIsAHelpEntry) {
  std::set<std::string> help;
  for (const HelpEntry& h : api_help()) help.insert(h.name);
  beltsim::script::Interpreter lua;
  lua_State* L = lua.state();
  ASSERT_EQ(lua_getglobal(L, "beltsim"), LUA_TTABLE);
  int keys = 0;
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    lua_pop(L, 1);
    ASSERT_EQ(lua_type(L, -1), LUA_TSTRING);
    const std::string key = lua_tostring(L, -1);
    ++keys;
    EXPECT_TRUE(help.count(key)) << "beltsim." << key << " has no help entry (script/lua_help.cpp)";
  }
  lua_pop(L, 1);
  EXPECT_GT(keys, 5);
}

TEST(LuaApiDocs, ReadsCallsWithPipesAndSeveralSpans) {
  EXPECT_EQ(first_cell_code("| `sim:set_mu(mu \\| f)` | does |"), std::vector<std::string>{"sim:set_mu(mu | f)"});
  EXPECT_EQ(first_cell_code("| `a`, `b` | `c` |"), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(call_of(HelpEntry{"x", "sim:x(t [s]) -> { t }", ""}), "sim:x(t [s])");
}

}  // namespace
