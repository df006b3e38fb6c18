// The message of the ParameterError (scene/validate.hpp) a call throws, empty when it throws none:
// the scene tests compare a refusal's whole text.
#pragma once

#include <string>

#include "scene/validate.hpp"

namespace beltsim::test {

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace beltsim::test
