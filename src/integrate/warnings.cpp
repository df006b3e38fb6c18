#include "integrate/warnings.hpp"
#include "io/number_text.hpp"

#include <algorithm>
#include <atomic>
#include <sstream>

namespace beltsim {

namespace {
std::atomic<WarningObserver> g_observer{nullptr};
}  // namespace

const std::array<WarningKindInfo, kWarningKinds>& warning_kinds() {
  static const std::array<WarningKindInfo, kWarningKinds> k{{
      {WarningKind::static_retry, "static_retry",
       "the static start needed its trust-region retry (the plain Newton iteration drifted along the belt)", false},
      {WarningKind::failed_step, "failed_step",
       "steps that could not be taken (the implicit iteration did not converge, or its matrix was singular); "
       "each was retried at a fifth of its size, and steps were kept below half of it for a while"},
      {WarningKind::cvode_convergence, "cvode_convergence",
       "CVODE's Newton iteration did not converge; CVODE retried the step shorter"},
      {WarningKind::cvode_nonfinite_rhs, "cvode_nonfinite_rhs",
       "CVODE tried a state whose forces were not finite; CVODE retried the step shorter"},
      {WarningKind::cvode_restart, "cvode_restart",
       "CVODE stalled (its steps over a window fell below the stall size) and was restarted from its current "
       "state at order 1 with a fresh Jacobian"},
  }};
  return k;
}

void Warnings::add(WarningKind k, double t, long n) {
  if (n <= 0) return;
  WarningStat& s = (*this)[k];
  if (s.count == 0) s.first_t = t;
  s.count += n;
  notify_warning(k, t, n);
}

bool Warnings::any() const {
  return std::any_of(stat.begin(), stat.end(), [](const WarningStat& s) { return s.count > 0; });
}

void Warnings::merge(const Warnings& o) {
  for (std::size_t k = 0; k < kWarningKinds; ++k) {
    const WarningStat& b = o.stat[k];
    WarningStat& a = stat[k];
    if (b.count == 0) continue;
    a.first_t = a.count == 0 ? b.first_t : std::min(a.first_t, b.first_t);
    a.count += b.count;
  }
}

std::string describe(WarningKind k, const WarningStat& s) {
  const WarningKindInfo& i = warning_kinds()[static_cast<std::size_t>(k)];
  return std::string(i.name) + ": " + std::to_string(s.count) + (s.count == 1 ? " time" : " times") +
         ", first at t = " + rounded_text(s.first_t) + " s (" + i.description + ")";
}

void set_warning_observer(WarningObserver o) { g_observer.store(o); }

void notify_warning(WarningKind k, double t, long n) {
  if (const WarningObserver o = g_observer.load(std::memory_order_relaxed)) o(k, t, n);
}

}  // namespace beltsim
