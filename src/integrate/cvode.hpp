// SUNDIALS CVODE (variable-order BDF with Newton) as the peer integrator, behind the same live
// Integrator interface as the one-step methods (integrate/integrator.hpp): samples at exact times by CVODE's own interpolation (CVodeGetDky), events landed on
// with CVodeSetStopTime and the integration restarted there (CVodeReInit), the stop flag, and
// DivergenceError naming the time and the component. For a piecewise-smooth F it also restarts
// at the kinks CVODE's rootfinding locates, and caps the error weights at the laws' resolution
// (CvodeSettings::kink_gap, resolve). Two variants:
//   "cvode"     our analytic Jacobian J = ∂F/∂y assembled sparse, solved by KLU
//   "cvode-fd"  a difference-quotient Jacobian on the pattern of the analytic one, its columns
//               coloured so that one perturbed right-hand side serves every column of a colour
//               (Curtis–Powell–Reid; CVODE's own difference quotients are for dense and banded
//               matrices only), solved by KLU
// Both run with the settings of CvodeSettings (the best found over the dry drive's whole second,
// docs/integration.md, "CVODE").
#pragma once

#include <string>
#include <vector>

#include "integrate/driver.hpp"

namespace beltsim {

// CVODE's optional inputs that matter here, and the adapter's own for a piecewise-smooth F; the
// defaults are the best configuration measured over the paper's dry second (docs/integration.md,
// "CVODE"), not CVODE's own defaults (noted per field)
struct CvodeSettings {
  int max_order = 2;               // BDF order limit (CVodeSetMaxOrd; CVODE: 5)
  double nonlin_conv_coef = 0.1;   // Newton's stopping test against the error test (CVodeSetNonlinConvCoef; CVODE: 0.1)
  long jac_eval_frequency = 10;    // steps between Jacobians (CVodeSetJacEvalFrequency; CVODE: 51)
  long lsetup_frequency = 5;       // steps between factorisations (CVodeSetLSetupFrequency; CVODE: 20)
  bool stab_lim_det = false;       // BDF stability limit detection (CVodeSetStabLimDet; CVODE: off)
  int max_nonlin_iters = 3;        // Newton iterations per step (CVodeSetMaxNonlinIters; CVODE: 3)
  // restart after a stall (not a CVODE input; the adapter's): when the last stall_window steps
  // advanced less than stall_window·stall_step seconds, CVODE is re-initialised at its current
  // state (CVodeReInit: order 1, a new history, a new Jacobian). 0 turns it off.
  long stall_window = 500;
  double stall_step = 1e-8;        // [s]
  // locate the kinks of F with CVODE's rootfinding (CVodeRootInit on OdeProblem::switches) and
  // restart there, so that no BDF history spans a kink, but no sooner than kink_gap steps after
  // the last restart: where the solution's error is as large as a kink's scale (a friction band
  // of 1e-5 m/s against rtol·|v| at loose tolerances) its switching function crosses zero every
  // step or two, and restarting at each crossing never lets the step grow. 0: no rootfinding
  // (not a CVODE input; the adapter's)
  long kink_gap = 20;
  // CVODE's error weights 1/(rtol·|y_k| + atol_k), with each component's tolerance held below
  // this fraction of OdeProblem::resolution (CVodeWFtolerances): at rtol 1e-5 a belt speed of
  // 2 m/s lets the velocity error be twice the friction band, and BDF then meets the band's kinks
  // at random. 0: CVODE's own weights (not a CVODE input; the adapter's)
  double resolve = 1;
};

bool is_cvode(const std::string& name);

DriveResult drive_cvode(const OdeSystem& sys, const std::string& name, const Tolerances& tol, const DriveOptions& opt,
                        Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress = {},
                        const CvodeSettings& settings = {});
std::unique_ptr<Integrator> make_cvode_integrator(const std::string& name, const OdeSystem& sys, const Tolerances& tol,
                                                  const CvodeSettings& settings = {});

// "order 2, coefficient 0.1, ..." for reports
std::string describe(const CvodeSettings& s);

}  // namespace beltsim
