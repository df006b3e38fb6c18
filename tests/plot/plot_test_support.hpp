// What the plot tests share: a fresh folder per test and a check of an error's message.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/scratch.hpp"

namespace beltsim::plot {

// a fresh folder per test, with a quote and a space in its name
inline std::filesystem::path dir(const std::string& name) {
  const std::filesystem::path d = beltsim::test::scratch_dir("beltsim plot's test") / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// f throws a std::runtime_error whose message has every one of parts
inline void expect_error(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    for (const auto& p : parts)
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what() << "\nlacks: " << p;
  }
}

}  // namespace beltsim::plot
