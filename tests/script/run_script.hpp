// Shared by the Lua API tests: write a script's text to a file, run it, and return the error.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "script/interpreter.hpp"
#include "support/warning_guard.hpp"  // a run's warnings fail the test unless expect_warnings declares them

namespace beltsim::script::test {

// writes text to path and runs it with lua (output folder `out` unless empty); returns the
// ScriptError's message ("file:line: ..."), or "" when the script ran
inline std::string run_script(Interpreter& lua, const std::filesystem::path& path, const std::string& text,
                              const std::filesystem::path& out = {}) {
  std::ofstream(path) << text;
  if (!out.empty()) {
    Overrides o;
    o.out = out.string();
    lua.set_overrides(o);
  }
  try {
    lua.run_file(path.string());
  } catch (const ScriptError& e) {
    return e.what();
  }
  return "";
}

// every part is in msg
inline void expect_has(const std::string& msg, const std::vector<std::string>& parts) {
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

}  // namespace beltsim::script::test
