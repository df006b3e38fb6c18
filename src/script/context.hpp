// Settings an interpreter passes to the bindings (private to src/script).
#pragma once

#include <atomic>
#include <string>

#include "script/interpreter.hpp"

namespace beltsim::script {

struct Context {
  Overrides overrides;
  std::string default_out = "out";        // out/<script name> while a script runs
  const std::atomic<bool>* stop = nullptr;
  bool interrupted = false;
  Captured* capture = nullptr;            // capture mode (see Interpreter::set_capture)
  bool captured = false;                  // the script was ended by a capture
};

}  // namespace beltsim::script
