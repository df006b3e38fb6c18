// Shared by lua_api_test.cpp and lua_api_runs_test.cpp: the test scene, a script run from its text.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "run_script.hpp"
#include "script/interpreter.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script::lua_api_test {

namespace fs = std::filesystem;

inline fs::path temp_dir() {
  return beltsim::test::scratch_dir("beltsim_lua_test");
}

// A valid two-pulley scene; belt_extra adds keys to the belt table, driven replaces the driven
// pulley's geometry.
inline std::string scene_text(const std::string& belt_extra,
                              const std::string& driven = "centre = {0.29, 0}, radius = 0.1") {
  beltsim::test::TwoPulley p;
  p.driven_at = driven, p.elements = 60, p.belt = belt_extra;
  return beltsim::test::two_pulley(p);
}

// runs the text as a script file and returns the error message ("" when it ran)
inline std::string run_text(const std::string& text, const std::string& name = "scene.lua") {
  Interpreter lua;
  return test::run_script(lua, temp_dir() / name, text, temp_dir() / "out");
}

inline void expect_error(const std::string& text, const std::string& where, const std::vector<std::string>& parts) {
  const std::string msg = run_text(text);
  ASSERT_FALSE(msg.empty()) << "no error for:\n" << text;
  EXPECT_NE(msg.find(where), std::string::npos) << msg;
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

}  // namespace beltsim::script::lua_api_test
