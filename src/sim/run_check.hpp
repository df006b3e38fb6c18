// A run's estimate of its own error (issue 42 §2; run{ check = true }, `beltsim run --check`).
//
// A companion solution at a tolerance kCheckTighten times tighter (rtol/10, atol/10), by the same
// integrator, is advanced in lockstep with the run over the one schedule (integrate/timeline.hpp:
// the same sample times, landings and restarts; a jump of the state made at a change applied to
// both). At every sample the run's pulley speeds and span tensions are compared with the
// companion's (sim/run_error.hpp, as §1 and `beltsim wp` measure):
//   estimate = max over channels and samples of |x(rtol) - x(rtol/10)| / max |x(rtol/10)|
// which is the run's true error when the error falls with the tolerance (the companion's own is
// then a tenth of it). A pulley's speed is measured against at least 1 rad/s, the size its
// absolute tolerance is per: a drive starting from rest is not measured against its first
// hundredths of a rad/s. The run warns, once, the first time the estimate so far (relative to
// the largest values so far) passes kCheckAlarm·rtol, and reports the estimate over the whole run
// at its end (parameters.csv check.*, the closing line), as a warning when past the accuracy
// contract's bounds (the speeds' kCheckSpeedLimit·rtol, the span tensions' kCheckTensionLimit·rtol).
//
// The estimate sees only what the two solutions do not share. At a tenth of the tolerance a run
// whose steps the tolerance sets takes 10^(1/(q+1)) times the steps, q its error order (2.2 for
// trbdf2 and esdirk32; 2.2 to 4.4 measured on the matrix's rows where the tolerance sets the
// steps). Where something else sets them (the growth limit of a falling friction curve, the
// first step's limit, failed iterations), the companion takes nearly the run's steps and carries
// nearly its error, and the estimate can be low: on the half-wet drive under Stribeck's law at
// rtol 1e-4 the companion took the run's steps (31 479) and the estimate of the span tensions
// was 1.5e-4 against a true 1.1e-3 to 1.6e-3 (two references). So the run also compares the
// step counts: below kCheckSharedSteps times the run's, the closing line warns that the estimate
// may be low.
#pragma once

#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/run_error.hpp"
#include "sim/run_settings.hpp"

namespace beltsim {

class BeltSystem;
class Integrator;
struct Drive;
struct Model;

constexpr double kCheckTighten = 10;  // the companion's tolerance: rtol / kCheckTighten
// The run's error from the difference of the two solutions: where the error is proportional to the
// tolerance (what the contract rests on) the companion carries a tenth of the run's, and
// |x - x_companion| is 9/10 of the run's error. Measured before this factor, over 44 runs of seven
// scenes against references at rtol 1e-7, the difference was 0.73 to 1.25 times the true error, its
// median 0.9 (a user's trial, 2026-12-02; docs/accuracy.md)
constexpr double kCheckProportional = kCheckTighten / (kCheckTighten - 1);
// an estimate above this share of its limit is near it: with the estimate some 0.8 to 1.4 times the
// true error (above), the run may be past the limit; the closing line says so as a warning
constexpr double kCheckNear = 0.7;

// What the drive has that the default integrator was measured not to keep the accuracy contract
// with at this rtol (the matrix's rows, docs/accuracy.md): a sentence for each, none when the
// contract held on every row like it. A run that does not check its own error warns of each when
// it starts, and of one that a change brings (a stretch wetted, a spray zone) when it is made.
std::vector<std::string> scene_contract_misses(const Model& m, const Drive& d, double rtol);
// whether those hold the overrunning decoupler's (a one-way coupling at rtol <= 1e-3)
bool decoupler_contract_miss(const Model& m, double rtol);

// a run's closing line warns past the accuracy contract's bounds (docs/accuracy.md): the pulley
// speeds past kCheckSpeedLimit·rtol, the span tensions past kCheckTensionLimit·rtol. While it runs,
// relative to the largest values so far (small in a start-up), it warns once when either passes
// kCheckAlarm·rtol: at the contract's 3·rtol the speeds' estimate so far passed it in the first
// milliseconds of the paper's dry drive at every rtol from 1e-3 to 1e-4
constexpr double kCheckSpeedLimit = 3;
constexpr double kCheckTensionLimit = 10;
constexpr double kContractRtol = 1e-3;  // the contract is promised at this rtol and below
// how a warning that a run may not keep it names the contract
constexpr const char* kContractText =
    "the accuracy contract (the pulley speeds within 3×rtol and the span tensions within 10×rtol; "
    "docs/accuracy.md): ";
constexpr double kCheckAlarm = 10;
// below this ratio of the companion's steps to the run's the two share their steps (above; the
// rows where the tolerance set the steps measured 2.2 to 4.4, those where it did not 0.75 to 1.2)
constexpr double kCheckSharedSteps = 1.3;

// what the check found so far
struct CheckEstimate {
  bool on = false;               // the run was checked
  double rtol = 0;               // the run's
  double err_speed = 0, err_tension = 0;  // the estimates (relative to the largest values)
  double warned_t = -1;          // [s] the first sample the estimate so far passed kCheckAlarm·rtol (-1: never)
  std::string failed;            // why the companion stopped early ("" when it did not)
  double steps_ratio = 0;        // the companion's accepted steps over the run's (0: none yet)
  double speed_limit() const { return kCheckSpeedLimit * rtol; }
  double tension_limit() const { return kCheckTensionLimit * rtol; }
  bool speeds_over() const { return err_speed > speed_limit(); }
  // the estimate over the run is past a limit
  bool over() const { return speeds_over() || err_tension > tension_limit(); }
  // the estimate so far is past kCheckAlarm·rtol (the warning while the run goes on)
  bool alarm() const { return std::max(err_speed, err_tension) > kCheckAlarm * rtol; }
  // the companion took so few more steps than the run that it shares the run's error
  bool shared() const { return steps_ratio > 0 && steps_ratio < kCheckSharedSteps; }
  // within the limits, but one of the estimates above kCheckNear of its limit
  bool near() const {
    return !over() && (err_speed > kCheckNear * speed_limit() || err_tension > kCheckNear * tension_limit());
  }
  // the closing line is a warning: past the limit, near it, or an estimate that may be low
  bool warns() const { return over() || near() || shared(); }
};

class RunCheck {
 public:
  // the companion of a run of sc with these settings, on the run's drive (read, not copied: the
  // drive's changes and the restart time are the run's)
  RunCheck(const Scene& sc, const Drive& drive, const RunSettings& rs);
  ~RunCheck();
  Integrator& integrator() { return *integ_; }
  // a sample of the run at t: y its state, yc the companion's there (null when the companion has
  // failed: failed says why), run_steps the run's accepted steps so far
  void sample(double t, const Eigen::VectorXd& y, const Eigen::VectorXd* yc, const std::string& failed,
              long run_steps);
  const CheckEstimate& estimate() const { return est_; }
  // "check: estimated error of the pulley speeds 2.1e-3, of the span tensions 4e-4 (relative to
  // their largest values over the run; rtol 0.001, companion at 0.0001)", with what is wrong when
  // it passed the limit or the companion failed
  std::string line() const;
  // parameters.csv's rows of the check (name,value,unit,source,note)
  std::string parameter_rows() const;

 private:
  const Scene& sc_;
  const Drive& drive_;
  const RunSettings& rs_;
  std::unique_ptr<BeltSystem> sys_;
  std::unique_ptr<Integrator> integ_;
  ErrorMeter speed_, tension_;
  std::vector<double> s_, t_, sc_s_, sc_t_;  // channels of the run and of the companion
  CheckEstimate est_;
};

// the tolerances of the companion of a run at these (rtol / kCheckTighten, atol likewise)
double check_rtol(const RunSettings& rs);

}  // namespace beltsim
