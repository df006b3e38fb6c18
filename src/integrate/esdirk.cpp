// ESDIRK stepper with a semi-smooth Newton iteration on every implicit stage.
//
// Stage i solves G(Z) = Z - h·γ·F(t_i, Z) - ψ_i = 0, ψ_i = y + h·Σ_{j<i} a_ij·F_j. Newton:
//   (s·I - J(Z))·ΔZ = -s·G(Z),   s = 1/(h·γ)
// with J refreshed at every iterate. The right-hand side is piecewise smooth (contact onset,
// p = p_max, N = 0, the friction band |v_T| < Δv whose slope μN/(m·Δv) ≈ 5e9 1/s): a frozen
// Jacobian from the step's start (Rosenbrock, simplified Newton) carries the wrong branch
// across a stick/slip change and fails; the refreshed one is a semi-smooth Newton step that
// settles each element on its branch within a few iterations. The stage derivative is then
// recovered without a further evaluation as F_i = (Z - ψ_i)·s. The error estimate
// h·Σ (b_j - b̂_j)·F_j is filtered through (I - h·γ·J)^-1 (Shampine; Hairer & Wanner IV.8),
// which keeps it meaningful on the stiff components.
// The dense output of a method whose stage values carry it (trbdf2: the quadratic P through y at
// the step's start, the trapezoidal stage Z1 at c1 = 2γ and y1; OneStep) reads the stage, whose
// error the estimate above does not measure: over a step long against a slow swing of the drive
// (the light belt's driven pulley at the start, steps of 29 ms over a swing of some 45 ms) the
// stage was 5e-3 off where both ends were within 9e-4. Its error is estimated from the defect of
// P, d(θ) = P'(θ)/h - F(t + θh, P(θ)): the error E = P - y obeys E' = d + J·E, so
//   E(c1) ≈ (I - h·γ·J)^-1 · c1·h·d(c1/2)
// (the midpoint rule over [0, c1], filtered as err is so that the stiff components' defect, their
// λ times a deviation the method damps, counts only as much as the deviation), at the price of one
// evaluation of F and one solve a step; the driver holds the answer's speeds there to the
// tolerance as at the step's end (Stepper::interior_error, StepController::interior_norm).
// A converged stage with h·γ·ρ > 1, ρ the fastest growth of a single variable at it
// (NewtonAids::unstable_rate: an element slipping on a falling friction curve), has lost that
// growth and may be a root the motion never visits (newton_aids.cpp, Falling friction): the step is
// refused, and every step is kept to h·γ·ρ <= kGrowth, ρ the largest of its stages.
#include <algorithm>
#include <cmath>
#include <limits>

#include "integrate/controller.hpp"
#include "integrate/stepper.hpp"
#include "integrate/tableau.hpp"

namespace beltsim {

namespace {

class Esdirk final : public Stepper {
 public:
  explicit Esdirk(const EsdirkTableau& tab) : tab_(tab) {}
  std::string name() const override { return tab_.name; }
  int order() const override { return tab_.order; }
  int embedded_order() const override { return tab_.embedded_order; }
  void attach(const StepController& ctl) override { ctl_ = &ctl; }
  double h_limit() const override { return h_limit_; }
  // the stage values strictly inside the step, where the tableau says they serve (trbdf2's
  // trapezoidal stage at 2γ)
  void interior(std::vector<double>& c, std::vector<Eigen::VectorXd>& Z) const override {
    const int k = tab_.interior_stages ? tab_.stages - 2 : 0;
    c.resize(k), Z.resize(k);
    for (int i = 0; i < k; ++i) c[i] = tab_.c[i + 1], Z[i] = stage_[i + 1];
  }
  bool needs_linear_solver() const override { return true; }
  bool l_stable() const override { return true; }  // both tableaus (tableau.cpp)

  bool step(const OdeSystem& sys, double t, const Eigen::VectorXd& y, const Eigen::VectorXd& f0, double h,
            Eigen::VectorXd& y1, Eigen::VectorXd& err) override {
    const EsdirkTableau& tab = tab_;
    aids_ = sys.aids ? sys.aids : &no_aids_;
    const int n = static_cast<int>(y.size());
    const int s = tab.stages;
    const double sh = 1.0 / (h * tab.gamma);
    F_.resize(s);
    stage_.resize(s);
    F_[0] = f0;
    Z_ = y;
    have_jac_ = false;
    h_limit_ = kInf;
    double rho = 0;  // the fastest growth of the stages so far
    for (int i = 1; i < s; ++i) {
      const double ti = t + tab.c[i] * h;
      psi_ = y;
      for (int j = 0; j < i; ++j) psi_ += (h * tab.a[i][j]) * F_[j];
      // predictor: the previous stage's value carried along its own motion to ti
      // (NewtonAids::predict; for the belt, elements in a wrap turn with it), not extrapolated
      // along the previous stage's slope: that would carry the stiff components (friction in
      // stick, ≈ 5e9 1/s) across their kinks and start Newton on the wrong branch for many
      // elements, each a failed iteration and often a shortened step.
      aids_->predict(t + tab.c[i - 1] * h, (tab.c[i] - tab.c[i - 1]) * h, Z_.data());
      if (!newton(sys, ti, sh, n)) return false;
      rho = std::max(rho, aids_->unstable_rate(ti, Z_.data()));
      if (rho > sh) {
        h_limit_ = kGrowth / (tab.gamma * rho);
        return false;
      }
      F_[i] = (Z_ - psi_) * sh;
      if (i + 1 < s) stage_[i] = Z_;
    }
    if (rho > 0) h_limit_ = kGrowth / (tab.gamma * rho);
    y1 = Z_;
    raw_.setZero(n);
    for (int j = 0; j < s; ++j) raw_ += (h * (tab.b[j] - tab.b_hat[j])) * F_[j];
    // filter: err = (I - hγJ)^-1 raw = s·(sI - J)^-1 raw, with J of the last stage
    err.resize(n);
    sys.linear->solve(raw_.data(), err.data());
    sys.problem->counters.solves++;
    err *= sh;
    return y1.allFinite();
  }

  bool interior_error(const OdeSystem& sys, double t, const Eigen::VectorXd& y, double h, double& c,
                      const Eigen::VectorXd*& Z, const Eigen::VectorXd*& e) override {
    if (!tab_.interior_stages) return false;
    interior_defect(sys, t, y, h, 1.0 / (h * tab_.gamma), static_cast<int>(y.size()));
    c = tab_.c[1], Z = &stage_[1], e = &eint_;
    return true;
  }

 private:
  // residual G(Z) = Z - ψ - F(t, Z)/s, in the units of the state; F(t, Z) kept in Fz
  double residual(const OdeSystem& sys, double t, double s, const Eigen::VectorXd& Z, Eigen::VectorXd& Fz,
                  Eigen::VectorXd& G) {
    sys.problem->rhs(t, Z.data(), Fz.data());
    sys.problem->counters.rhs++;
    G = Z - psi_ - Fz / s;
    return ctl_->weighted_norm(Z, G);
  }

  // semi-smooth Newton on G(Z) = 0; Z_ holds the predictor. The Jacobian and its factorisation
  // are reused within the step while the iterate stays on the same smooth piece of the
  // right-hand side (NewtonAids::branches) and the corrections contract by kRate or better;
  // otherwise they are refreshed at the current iterate. Three aids for the kinks:
  // - after every correction the system solves its stiffest local equations exactly
  //   (NewtonAids::local_solve: the tangential velocities of each wrap's elements against the
  //   friction band and their springs, everything else held), which settles every element on its
  //   stick or slip branch before the next Jacobian is taken;
  // - the system may put what a correction would carry across a branch onto it (NewtonAids::reseat:
  //   elements that would slip right across the friction band land in it). While corrections are
  //   taken whole, the reseat changes the correction and the rest of it is kept; once the line
  //   search guards the iteration, it moves the iterate and the iteration starts again from there;
  // - the first kFullSteps corrections are taken whole unless long (kFullNorm below; a
  //   full step that carries an element from stick to slip raises the residual until the next
  //   Jacobian sees the new branch); after that, and for a longer one, a backtracking line search
  //   on ‖G‖ guards against cycling between the two sides of a kink.
  // What each of these measured is in the commit messages that brought them (git log -S on their names).
  bool newton(const OdeSystem& sys, double t, double s, int n) {
    constexpr int max_iter = 12;
    constexpr int kFullSteps = 3;
    // a correction longer than kFullNorm tolerances, or than the state's own size (1/rtol
    // tolerances: each component moved by |y| or its natural size in the root mean square), is
    // not taken whole even among the first kFullSteps: the iterate is far from the stage's root (a
    // light element's contact or spring force swung by a long step), the Jacobian there holds for
    // a small part of the way, and the whole correction flings the element across many branches,
    // from which the iteration seldom comes back; the line search shortens it. On the light belt
    // of scripts/light_belt.lua the first corrections of a stage are some 7e3 tolerances at rtol
    // 1e-3. The state's size bounds it at loose tolerances: at rtol 1e-2, 1e3 tolerances let the
    // light belt take 7 times the steps of rtol 1e-3 over its first 0.1 s; a bound of the state's
    // size alone, 1e4 tolerances at 1e-4, took 5 times the steps at 240 elements over 2.45 s
    // (commit message).
    constexpr double kFullNorm = 1e3;
    constexpr double kRate = 0.3;
    constexpr double kAbsolute = 1e-6;  // kappa·rtol of a method whose stages are checked, above rtol 1e-4 (below)
    // converged when what a full correction leaves (kLeft below) is below kappa of the tolerance
    // and the correction carries no slip velocity more than a tenth of the friction band past the
    // band's edge (NewtonAids::overshoot).
    // The predictor often starts Newton close enough to stop after one or two corrections, so this
    // stop, more than the step size, limits how well a stage is solved.
    // A correction measures the iterate's remaining error only on one smooth piece of F, where the
    // next correction is far smaller. One that carries an element's slip velocity past an edge of
    // the band |v_T| < Δv by o·Δv was computed with the slope of the piece it leaves (μN/Δv in the
    // band, 0 outside): past the edge the element's friction force is wrong by up to μN·min(o, 2),
    // which reaches its pulley and neighbours through the next correction, however small this one
    // is against the tolerance. The norm does not see it at loose tolerances: the velocity
    // tolerance atol + rtol·|v| is about 0.04 m/s at rtol 1e-2 on a 3.4 m/s belt, four thousand
    // bands of 1e-5 m/s, and the norm's mean over all the states lets one element's correction be
    // √n times the rest. Such a stop leaves a step with a wrong friction force now and then, each a
    // spike in the pulley speeds larger than the tolerance asks. At rtol 1e-4 and below the norm
    // alone keeps the corrections within a band or two and the second test seldom decides. kBand
    // bounds the force an element is left with to a tenth of its μN.
    // kappa is 1e-4, not the 1e-2 of the textbooks (Hairer & Wanner IV.8), where the stages'
    // errors go unchecked: a stage the iteration leaves off carries an error that no estimate sees
    // (every stage carries it) and the pulleys take up. On the paper's drive with both pulleys at
    // 1e-4 kg·m² a stop at 1 % of the tolerance left the driver's speed 20 times the tolerance off
    // at rtol 1e-3; esdirk32's speeds on that drive with pulleys at 6e-6 kg·m² were 9e-2 off at
    // rtol 1e-3 with 1e-4 and 2.1 with 1e-3, and its run at rtol 1e-7 (the reference) 1e-5 off
    // with 1e-2, against 7e-7 (commit message).
    // A method whose dense output reads its stage (trbdf2) has the stage checked by the defect of
    // that output (interior_defect below), which sees what the iteration left there: kappa is the
    // textbooks' 1e-2 at rtol 1e-4 and tighter, and 1e-6/rtol above it (1e-3 at rtol 1e-3, 1e-4 at
    // 1e-2), since the friction band is a fixed width (Δv = 1e-5 m/s on the paper's drive, 1.4e-6
    // of its belt speed) and at loose tolerances the velocity tolerance is thousands of bands wide.
    // On the paper's drive at rtol 1e-3 trbdf2 took 942 steps over 0.3 s at 1e-2 and 551-567 at
    // 1e-4 and 1e-3; at rtol 1e-4, 1e-2 took 18-24 % fewer right-hand sides than 1e-4 on the dry
    // and automotive drives, the light pulleys and the serpentine, for the same steps and errors
    // (commit message).
    // (at tolerances near the rounding of the state, a correction at the rounding noise of the
    // residual, a thousand units of rounding of the state on the belt's stiff stages, is as
    // converged as it gets: the bound never falls below that)
    const double rounding = 1e3 * std::numeric_limits<double>::epsilon() / ctl_->rtol();
    const double kappa =
        std::max(tab_.interior_stages ? std::clamp(kAbsolute / ctl_->rtol(), 1e-4, 1e-2) : 1e-4, rounding);
    // What a correction leaves: when it and the one before it are both taken whole, about θ/(1-θ)
    // of it, θ the ratio of their norms (the iteration's contraction; Hairer & Wanner IV.8);
    // otherwise all of it. The stop above asks that of what is left. It counts at least kLeft of
    // the correction: at loose tolerances a correction many bands long in a slip velocity leaves
    // more than two norms tell (esdirk32 at rtol 8e-3 to 1.4e-2 on the paper's drive,
    // loose_tolerance_test: counting 1 %, the pulley speeds up to 2.9e-2 off; 3 %, within the
    // tolerance). At the rounding's stop the corrections are noise, and θ with them: there all of
    // the correction counts (the mode checks' runs at rtol 1e-10, mode_check.hpp).
    const double kLeft = rounding < 1e-4 ? 0.03 : 1.0;
    constexpr double kBand = 0.1;
    // a correction below 5 % of the tolerance is taken whole by the line search: near convergence
    // the residual is at rounding level and need not decrease, and a search that demanded it would
    // give up on stages whose reused Jacobian still contracts, each a failed step. It sits above
    // kappa so that such a stage takes its last few corrections whole and converges (a tenth as
    // many failed steps as with the bound at kappa, for 9 % more Jacobians)
    constexpr double kTakeWhole = 0.05;
    Fz_.resize(n), Ft_.resize(n), G_.resize(n), Gt_.resize(n), dZ_.resize(n), Zt_.resize(n);
    double r = residual(sys, t, s, Z_, Fz_, G_);
    double prev_norm = 0;
    bool prev_whole = false;  // the previous correction was taken whole (no line search, no reseat)
    bool refresh = false;
    for (int it = 0; it < max_iter; ++it) {
      if (!std::isfinite(r)) return false;
      const uint64_t sig = aids_->branches(t, Z_.data());
      const bool reuse = have_jac_ && !refresh && sig != 0 && sig == jac_sig_;
      if (!reuse) {
        if (!sys.linear->prepare_jacobian(t, Z_.data())) return false;
        sys.problem->counters.jacobians++;
        if (!sys.linear->factor(s)) return false;
        sys.problem->counters.factorizations++;
        have_jac_ = true, jac_sig_ = sig;
      }
      refresh = false;
      rhs_ = -s * G_;
      sys.linear->solve(rhs_.data(), dZ_.data());
      sys.problem->counters.solves++;
      const double step_norm = ctl_->weighted_norm(Z_, dZ_);
      if (!std::isfinite(step_norm)) return false;
      // a reused Jacobian that no longer contracts fast is refreshed at the next iterate
      if (reuse && it > 0 && step_norm > kRate * prev_norm) refresh = true;
      const double theta = prev_whole ? step_norm / prev_norm : 1.0;
      const double left = theta < 1 ? step_norm * std::clamp(theta / (1 - theta), kLeft, 1.0) : step_norm;
      prev_norm = step_norm;
      prev_whole = false;
      if (left <= kappa && aids_->overshoot(t, Z_.data(), dZ_.data()) <= kBand) {
        // converged: take the (tiny) correction as it is
        Z_ += dZ_;
        return true;
      }
      const bool whole = it < kFullSteps && step_norm <= std::min(kFullNorm, 1 / ctl_->rtol());
      if (whole) {
        aids_->reseat(t, Z_.data(), dZ_.data(), true);
      } else if (aids_->reseat(t, Z_.data(), dZ_.data(), false)) {
        r = residual(sys, t, s, Z_, Fz_, G_);
        continue;
      }
      double lambda = 1.0, rt = 0;
      for (;;) {
        Zt_ = Z_ + lambda * dZ_;
        rt = residual(sys, t, s, Zt_, Ft_, Gt_);
        if (whole || lambda * step_norm <= kTakeWhole || rt <= (1 - 1e-4 * lambda) * r ||
            lambda < 1.0 / 64)
          break;
        lambda *= 0.5;
      }
      Z_.swap(Zt_);
      Fz_.swap(Ft_);
      G_.swap(Gt_);
      r = rt;
      prev_whole = lambda == 1.0;
      if (aids_->local_solve(t, s, Z_.data(), G_.data())) r = residual(sys, t, s, Z_, Fz_, G_);
      if (lambda < 1.0 / 64) return false;  // no descent: give up, the step will be shortened
    }
    return false;
  }

  // eint_ = (I - hγJ)^-1 · c1·h·d(c1/2), d the defect of the quadratic through y (θ = 0), the stage
  // Z1 (θ = c1) and y1 (θ = 1) (see the top of the file)
  void interior_defect(const OdeSystem& sys, double t, const Eigen::VectorXd& y, double h, double sh, int n) {
    const double c = tab_.c[1], th = 0.5 * c;
    const double l0 = (th - c) * (th - 1) / c, l1 = th * (th - 1) / (c * (c - 1)), l2 = th * (th - c) / (1 - c);
    const double d0 = (2 * th - c - 1) / c, d1 = (2 * th - 1) / (c * (c - 1)), d2 = (2 * th - c) / (1 - c);
    const Eigen::VectorXd& Z1 = stage_[1];
    Zt_ = l0 * y + l1 * Z1 + l2 * Z_;
    Ft_.resize(n);
    sys.problem->rhs(t + th * h, Zt_.data(), Ft_.data());
    sys.problem->counters.rhs++;
    raw_ = c * (d0 * y + d1 * Z1 + d2 * Z_) - (c * h) * Ft_;
    eint_.resize(n);
    sys.linear->solve(raw_.data(), eint_.data());
    sys.problem->counters.solves++;
    eint_ *= sh;
  }

  static constexpr double kInf = std::numeric_limits<double>::infinity();
  // the largest h·γ·ρ a step is planned for, from the growth its predecessor met: below the
  // refusal at 1, since the growth changes from step to step as elements reach the falling curve
  static constexpr double kGrowth = 0.7;
  const EsdirkTableau& tab_;
  const StepController* ctl_ = nullptr;
  double h_limit_ = kInf;  // h_limit() of the last step
  NewtonAids no_aids_;                 // for a system without aids: each does nothing
  NewtonAids* aids_ = &no_aids_;
  bool have_jac_ = false;  // a Jacobian taken in this step is factored (all stages share h·γ)
  uint64_t jac_sig_ = 0;   // the branches it was taken on
  std::vector<Eigen::VectorXd> F_;
  std::vector<Eigen::VectorXd> stage_;  // the stage values of the last step (interior)
  Eigen::VectorXd Z_, Zt_, psi_, G_, Gt_, dZ_, raw_, rhs_, Fz_, Ft_, eint_;
};

}  // namespace

std::unique_ptr<Stepper> make_esdirk() { return std::make_unique<Esdirk>(esdirk32()); }
std::unique_ptr<Stepper> make_trbdf2() { return std::make_unique<Esdirk>(trbdf2()); }

}  // namespace beltsim
