// Tests fail on warnings they did not expect (as MuJoCo's test fixture fails on any engine
// warning): warning_guard.cpp, linked into a test program, watches every warning a test's runs
// fire (integrate/warnings.hpp) and fails the test at its end for each kind it did not declare.
#pragma once

#include <initializer_list>

#include "integrate/warnings.hpp"

namespace beltsim::test {

// declares that the running test may fire these kinds (each call adds to the list)
void expect_warnings(std::initializer_list<WarningKind> kinds);

}  // namespace beltsim::test
