#include "sim/run_check.hpp"

#include <cstdio>
#include <sstream>

#include "integrate/belt_system.hpp"
#include "integrate/make_integrator.hpp"
#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "scene/scene.hpp"

namespace beltsim {

namespace {
// [rad/s] the least scale of a pulley's speed: the size its absolute tolerance is per
// (BeltProblem::kNaturalSizes)
constexpr double kSpeedFloor = 1.0;

// "pulley speeds is 0.0042 (relative to their largest values ...), past 3×rtol = 0.003": the
// speeds' estimate (else the span tensions') past factor·rtol; over_run: relative to the whole run's
std::string past(const CheckEstimate& e, bool speeds, double factor, bool over_run) {
  return std::string(speeds ? "pulley speeds" : "span tensions") + " is " +
         rounded_text(speeds ? e.err_speed : e.err_tension, 3) + " (relative to their largest values " +
         (over_run ? "over the run" : "so far") + "), past " + rounded_text(factor) + "×rtol = " +
         rounded_text(factor * e.rtol);
}

// two significant digits, a trailing zero kept: 4.0e-05, 0.00030 (rounded_text's 4e-05 and 0.0003
// read as one digit)
std::string two_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%#.2g", v);
  return buf;
}
}  // namespace

std::vector<std::string> scene_contract_misses(const Model& m, const Drive& d, double rtol) {
  // measured with trbdf2 against esdirk32 at rtol 1e-7 (beltsim wp on the rows of
  // bench/accuracy_matrix.csv, 2026-11-30; the wet row at 24 tolerances, 2026-12-01); the bounds:
  // speeds 3·rtol, span tensions 10·rtol
  std::vector<std::string> out;
  if (m.any_law(FrictionKind::stribeck) && rtol < 1e-3)
    out.push_back(
        "under Stribeck's law the falling friction curve, not the tolerance, sets the steps below rtol "
        "1e-3, and the error stops falling (on the paper's half-wet drive the span tensions were 1.7e-3 to "
        "8.8e-3 off at rtol 1e-3 and 1.3e-3 to 1.0e-2 at 1e-4, the pulley speeds 3.7e-5 to 4.6e-4 at 1e-4)");
  if (decoupler_contract_miss(m, rtol))
    out.push_back(
        "with an overrunning decoupler the span tensions' error reaches 6 to 18 times rtol at and below "
        "rtol 1e-3 (5.6e-3 to 1.1e-2 at rtol 1e-3, 1.1e-3 to 1.8e-3 at 1e-4, as the run's steps fall; measured "
        "on a drive whose clutch overruns after a gear shift: the summary's overrun_count says whether yours "
        "did)");
  const bool wet = d.spray.any() || std::any_of(d.mu.begin(), d.mu.end(), [&](double mu) { return mu != d.mu[0]; });
  if (wet)
    out.push_back(
        "where μ changes along the belt (a wet stretch, a spray zone) a pulley that slipped on it and grips "
        "again steps its span tensions at a moment only as right as the speeds: on the paper's half-wet "
        "drive (115 N in 1 ms at 0.381 s) they were 4.5 to 53 times rtol off there at 24 tolerances from "
        "5e-6 to 1e-3, past 10 times at 7 of them");
  return out;
}

bool decoupler_contract_miss(const Model& m, double rtol) {
  return rtol <= 1e-3 &&
         std::any_of(m.couplings.begin(), m.couplings.end(), [](const Coupling& c) { return c.one_way; });
}

double check_rtol(const RunSettings& rs) {
  return rs.rtol / kCheckTighten;
}

RunCheck::RunCheck(const Scene& sc, const Drive& drive, const RunSettings& rs)
    : sc_(sc),
      drive_(drive),
      rs_(rs),
      speed_(static_cast<size_t>(sc.model.n_p()), kSpeedFloor),
      tension_(sc.route.spans.size()) {
  sys_ = std::make_unique<BeltSystem>(sc.model, drive);
  sys_->problem.set_spans(sc.route.span_middles());  // the answer's span tensions, as the run's
  const Tolerances tol{rs.rtol, rs.atol};
  integ_ = make_integrator(rs.integrator, *sys_, Tolerances{check_rtol(rs), tol.absolute() / kCheckTighten});
  est_.on = true;
  est_.rtol = rs.rtol;
}

RunCheck::~RunCheck() = default;

void RunCheck::sample(double t, const Eigen::VectorXd& y, const Eigen::VectorXd* yc, const std::string& failed,
                      long run_steps) {
  if (!yc) {
    est_.failed = failed;
    return;
  }
  speeds_and_tensions(sc_, drive_, t, y.data(), s_, t_);
  speeds_and_tensions(sc_, drive_, t, yc->data(), sc_s_, sc_t_);
  speed_.add(s_.data(), sc_s_.data());
  tension_.add(t_.data(), sc_t_.data());
  est_.err_speed = kCheckProportional * speed_.error();
  est_.err_tension = kCheckProportional * tension_.error();
  if (run_steps > 0) est_.steps_ratio = static_cast<double>(sys_->problem.counters.steps) / run_steps;
  if (est_.warned_t >= 0 || !est_.alarm()) return;
  est_.warned_t = t;
  if (!rs_.on_warning) return;
  const bool speeds = est_.err_speed > kCheckAlarm * est_.rtol;
  rs_.on_warning("check: at t = " + rounded_text(t) + " s the estimated error so far of the " +
                 past(est_, speeds, kCheckAlarm, false) +
                 ": this run's answer is not within its tolerance; try a tighter rtol");
}

std::string RunCheck::line() const {
  std::string s = "check: estimated error of the pulley speeds " + two_digits(est_.err_speed) +
                  ", of the span tensions " + two_digits(est_.err_tension) +
                  " (relative to their largest values over the run; rtol " + rounded_text(rs_.rtol) +
                  ", companion at " + rounded_text(check_rtol(rs_)) + ")";
  const std::string limits = "3×rtol = " + rounded_text(est_.speed_limit()) +
                             " for the speeds, 10×rtol = " + rounded_text(est_.tension_limit()) +
                             " for the span tensions";
  const std::string promised = est_.rtol > kContractRtol ? " (promised at rtol 1e-3 and below)" : "";
  if (est_.over()) {
    s += "; the estimate of the " +
         past(est_, est_.speeds_over(), est_.speeds_over() ? kCheckSpeedLimit : kCheckTensionLimit, true) +
         ": do not trust this run's answer at this tolerance";
  } else if (est_.near()) {
    const bool speeds = est_.err_speed > kCheckNear * est_.speed_limit();
    s += "; the estimate of the " + std::string(speeds ? "pulley speeds" : "span tensions") + " is within " +
         rounded_text(100 * (1 - kCheckNear)) + " % of its limit (" + limits + promised +
         "): the estimate is some 0.8 to 1.4 times the true error, so the run may be past it; confirm at a "
         "tighter rtol before quoting it";
  } else {
    s += "; within the accuracy contract's " + limits + promised;
  }
  if (!est_.over() && est_.warned_t >= 0)
    s += "; it passed " + rounded_text(kCheckAlarm) + "×rtol at t = " + rounded_text(est_.warned_t) +
         " s, relative to the smaller values then";
  if (est_.shared())
    s += "; the companion took only " + rounded_text(est_.steps_ratio, 2) +
         " times the run's steps (where the tolerance sets the steps, 2 to 4 times): something else sets them "
         "(a falling friction curve's growth limit, failed iterations, the first step's limit), the two solutions "
         "share that error and the estimate may be low; compare with a run at a tighter rtol";
  if (!est_.failed.empty())
    s += "; the companion stopped early, the estimate covers the run up to then: " + est_.failed;
  return s;
}

std::string RunCheck::parameter_rows() const {
  std::ostringstream f;
  auto row = [&](const char* name, const std::string& v, const char* note) {
    f << name << ',' << v << ",,derived," << csv_text(note) << '\n';
  };
  row("check.rtol", value_text(check_rtol(rs_)), "the companion solution's rtol (its atol likewise a tenth)");
  row("check.err_speed", value_text(est_.err_speed),
      "estimated error of the pulley speeds: 10/9 of the max over pulleys and samples of |run - companion|, "
      "relative to the companion's largest |speed| of that pulley (at least 1 rad/s)");
  row("check.err_tension", value_text(est_.err_tension), "the same for the span tensions");
  row("check.limit_speed", value_text(est_.speed_limit()),
      "3×rtol: the run warns where the speeds' estimate passes it");
  row("check.limit_tension", value_text(est_.tension_limit()),
      "10×rtol: the run warns where the span tensions' estimate passes it");
  row("check.over", est_.over() ? "1" : "0", "1: the estimate over the run is past a limit");
  row("check.near", est_.near() ? "1" : "0",
      "1: within the limits but above 0.7 of one, where the run may be past it (the estimate is some 0.8 to 1.4 "
      "times the true error); the closing line warned");
  row("check.steps_ratio", value_text(est_.steps_ratio),
      "the companion's accepted steps over the run's; below 1.3 the two share their steps and the estimate may be "
      "low (where the tolerance sets the steps, 2 to 4)");
  row("check.shared", est_.shared() ? "1" : "0", "1: the steps ratio is below 1.3, the closing line warned");
  row("check.warned_t", est_.warned_t >= 0 ? value_text(est_.warned_t) : std::string(),
      "simulated time [s] the estimate so far first passed 10×rtol, when the run warned (empty: never)");
  row("check.failed", csv_text(est_.failed), "why the companion stopped early (empty: it did not)");
  return f.str();
}

}  // namespace beltsim
