// Fallbacks a run takes, counted as MuJoCo counts its warnings (mjWarningStat): for each kind, how
// often it fired and the simulated time it first did. One table (warning_kinds()) names and
// describes every kind; the run's summary line, Simulation::notes() and the warning.* rows of
// parameters.csv are all made from it.
#pragma once

#include <array>
#include <cstddef>
#include <string>

namespace beltsim {

enum class WarningKind {
  static_retry,         // the static start's trust-region retry (scene/scene.cpp)
  failed_step,          // a one-step implicit method's step could not be taken (integrate/one_step.cpp)
  cvode_convergence,    // CVODE's Newton iteration did not converge (integrate/cvode.cpp)
  cvode_nonfinite_rhs,  // CVODE tried a state whose right-hand side is not finite (integrate/cvode.cpp)
  cvode_restart,        // CVODE stalled and was restarted from its current state (integrate/cvode.cpp)
};
constexpr std::size_t kWarningKinds = 5;

struct WarningKindInfo {
  WarningKind kind;
  const char* name;         // warning.<name> in parameters.csv
  const char* description;  // what happened and what beltsim did about it
  // named in a run's closing `warnings:` line too (false: parameters.csv and notes() only, for a
  // fallback that always ends well, as the static start's retry, which converged or the build is
  // refused: on a plain three-pulley drive it closed every run)
  bool closing_line = true;
};
// every kind, in WarningKind's order
const std::array<WarningKindInfo, kWarningKinds>& warning_kinds();

struct WarningStat {
  long count = 0;
  double first_t = -1;  // [s] simulated time it first fired; -1: never
};

struct Warnings {
  std::array<WarningStat, kWarningKinds> stat{};
  // n more of kind k at time t (the first time is kept); tells the observer (notify_warning)
  void add(WarningKind k, double t, long n = 1);
  const WarningStat& operator[](WarningKind k) const { return stat[static_cast<std::size_t>(k)]; }
  WarningStat& operator[](WarningKind k) { return stat[static_cast<std::size_t>(k)]; }
  bool any() const;
  // the sum of two (a run's integrator and its scene): counts added, the earlier first time
  void merge(const Warnings& o);
};

// "failed_step: 15 times, first at t = 0.036 s (<description>)" for each kind that fired
std::string describe(WarningKind k, const WarningStat& s);

// A process-wide observer told of every warning as it fires (tests use it to fail on warnings
// they did not expect, as MuJoCo's test fixture does; tests/support/warning_guard.hpp). nullptr:
// none. Not for a program's own use: a run reads its counts from its Simulation.
using WarningObserver = void (*)(WarningKind k, double t, long n);
void set_warning_observer(WarningObserver o);
// tells the observer, if one is set (Warnings::add does; a fallback counted elsewhere, such as
// Scene::static_retried, calls it where it happens)
void notify_warning(WarningKind k, double t, long n = 1);

}  // namespace beltsim
