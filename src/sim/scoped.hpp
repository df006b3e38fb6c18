// A guard that sets a variable for its scope (sim/simulation.cpp, simulation_callbacks.cpp: the
// view a when-condition reads, the flag of a callback's function running).
#pragma once

#include <utility>

namespace beltsim {

// sets a variable for the guard's scope and gives it back its value before, however the scope is
// left (an exception from a Lua callback included)
template <class T>
class Scoped {
 public:
  Scoped(T& var, T value) : var_(var), saved_(std::exchange(var, std::move(value))) {}
  ~Scoped() { var_ = std::move(saved_); }
  Scoped(const Scoped&) = delete;
  Scoped& operator=(const Scoped&) = delete;

 private:
  T& var_;
  T saved_;
};

}  // namespace beltsim
