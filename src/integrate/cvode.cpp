#include "integrate/cvode.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <sstream>
#include <utility>

#include <Eigen/SparseCore>

#include "integrate/colouring.hpp"
#include "integrate/controller.hpp"
#include "integrate/integrator.hpp"
#include "io/number_text.hpp"

namespace beltsim {

bool is_cvode(const std::string& name) { return name == "cvode" || name == "cvode-fd"; }

namespace {

struct Session {
  OdeProblem* problem = nullptr;
  LinearSolver* linear = nullptr;  // its sparse Jacobian (the pattern, and for "cvode" the values)
  Eigen::SparseMatrix<double> J;  // analytic Jacobian, CSC; for cvode-fd only its pattern is used
  ColumnColouring colouring;      // cvode-fd: the columns of J's pattern that share one perturbation
  std::vector<double> work;       // cvode-fd: scratch of the difference quotients
  long fd_rhs = 0;                // right-hand sides taken by the difference quotients (CVODE does not count them)
  std::string last_error;
  WorkCounters done;              // counters of the finished segments (CVodeReInit resets CVODE's)
  // an exception of the system (a law's code failed): kept here, since it must not unwind
  // through CVODE's C frames, and thrown again when CVode() returns
  std::exception_ptr error;
  Warnings warnings;              // the fallbacks, counted as they happen (not reset by CVodeReInit)
  long kink_restarts = 0;         // restarts at located kinks (CvodeSettings::kink_gap)
  // CvodeSettings::resolve: the relative tolerance, each component's absolute one and its cap
  double rtol = 0;
  std::vector<double> atol, cap;
};

// the error weights with the tolerances capped (CvodeSettings::resolve)
int weights_cb(N_Vector y, N_Vector ewt, void* user) {
  const Session& s = *static_cast<const Session*>(user);
  const double* yy = N_VGetArrayPointer(y);
  double* w = N_VGetArrayPointer(ewt);
  for (size_t k = 0; k < s.cap.size(); ++k) {
    const double tol = std::min(s.rtol * std::abs(yy[k]) + s.atol[k], s.cap[k]);
    if (!(tol > 0)) return -1;
    w[k] = 1 / tol;
  }
  return 0;
}

// the switching functions for CVODE's rootfinding
int switches_cb(sunrealtype t, N_Vector y, sunrealtype* g, void* user) {
  Session& s = *static_cast<Session*>(user);
  s.problem->switches(t, N_VGetArrayPointer(y), g);
  return 0;
}

int rhs_cb(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  Session& s = *static_cast<Session*>(user);
  const double* yy = N_VGetArrayPointer(y);
  double* dy = N_VGetArrayPointer(ydot);
  try {
    s.problem->rhs(t, yy, dy);
  } catch (...) {
    s.error = std::current_exception();
    return -1;  // unrecoverable: CVode returns at once
  }
  for (int k = 0, n = s.problem->size(); k < n; ++k)
    if (!std::isfinite(dy[k])) {
      s.warnings.add(WarningKind::cvode_nonfinite_rhs, t);
      return 1;  // recoverable: CVODE retries with a smaller step
    }
  return 0;
}

// s.J, pattern and values, into CVODE's CSC matrix (CVODE zeroes the whole matrix, index arrays
// included, before each Jacobian)
int copy_jacobian(const Session& s, SUNMatrix A) {
  const sunindextype nnz = s.J.nonZeros();
  if (SUNSparseMatrix_NNZ(A) < nnz && SUNSparseMatrix_Reallocate(A, nnz) != 0) return -1;
  sunindextype* ptr = SUNSparseMatrix_IndexPointers(A);
  sunindextype* idx = SUNSparseMatrix_IndexValues(A);
  double* val = SUNSparseMatrix_Data(A);
  for (Eigen::Index c = 0; c <= s.J.outerSize(); ++c) ptr[c] = s.J.outerIndexPtr()[c];
  for (sunindextype k = 0; k < nnz; ++k) idx[k] = s.J.innerIndexPtr()[k];
  for (sunindextype k = 0; k < nnz; ++k) val[k] = s.J.valuePtr()[k];
  return 0;
}

// J = ∂F/∂y from the system, copied into CVODE's CSC matrix (same pattern every call)
int jac_cb(sunrealtype t, N_Vector y, N_Vector, SUNMatrix A, void* user, N_Vector, N_Vector, N_Vector) {
  Session& s = *static_cast<Session*>(user);
  try {
    if (!s.linear->sparse_jacobian(t, N_VGetArrayPointer(y), s.J)) return -1;
  } catch (...) {
    s.error = std::current_exception();
    return -1;
  }
  s.J.makeCompressed();
  return copy_jacobian(s, A);
}

// J by coloured forward differences (integrate/colouring.hpp) on the analytic Jacobian's pattern;
// a non-finite F is recoverable: CVODE retries with a smaller step
int fd_jac_cb(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix A, void* user, N_Vector, N_Vector, N_Vector) {
  Session& s = *static_cast<Session*>(user);
  long taken = 0;
  try {
    taken = difference_jacobian(*s.problem, s.colouring, t, N_VGetArrayPointer(y), N_VGetArrayPointer(fy), s.J, s.work);
  } catch (...) {  // as in rhs_cb: kept, not unwound through CVODE
    s.error = std::current_exception();
    return -1;
  }
  if (taken < 0) {
    s.fd_rhs += s.colouring.colours;
    s.warnings.add(WarningKind::cvode_nonfinite_rhs, t);
    return 1;  // recoverable, as in rhs_cb
  }
  s.fd_rhs += taken;
  return copy_jacobian(s, A);
}

void err_cb(int code, const char* module, const char* function, char* msg, void* user) {
  if (code == CV_WARNING) return;
  static_cast<Session*>(user)->last_error = std::string(module) + " " + function + ": " + msg;
}

// adds CVODE's statistics to w
void add_counters(void* mem, WorkCounters& w) {
  long steps = 0, etf = 0, ncf = 0, nfe = 0, nfels = 0, nje = 0, nsetups = 0, nni = 0;
  CVodeGetNumSteps(mem, &steps);
  CVodeGetNumErrTestFails(mem, &etf);
  CVodeGetNumNonlinSolvConvFails(mem, &ncf);
  CVodeGetNumRhsEvals(mem, &nfe);
  CVodeGetNumLinRhsEvals(mem, &nfels);  // the difference-quotient Jacobian's evaluations
  CVodeGetNumJacEvals(mem, &nje);
  CVodeGetNumLinSolvSetups(mem, &nsetups);
  CVodeGetNumNonlinSolvIters(mem, &nni);
  w.steps += steps;
  w.rejected += etf + ncf;
  w.rhs += nfe + nfels;
  w.jacobians += nje;
  w.factorizations += nsetups;
  w.solves += nni;
}

// owns the SUNDIALS objects of one run
struct Cvode {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr, abstol = nullptr, dky = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  void* mem = nullptr;
  ~Cvode() {
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    for (N_Vector v : {y, abstol, dky})
      if (v) N_VDestroy(v);
    if (ctx) SUNContext_Free(&ctx);
  }
};

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string("cvode: ") + what + " failed (" + CVodeGetReturnFlagName(flag) + ")");
}

// the optional inputs (CVodeReInit keeps them); after the linear solver is attached
void apply(void* mem, const CvodeSettings& s) {
  check(CVodeSetMaxOrd(mem, s.max_order), "CVodeSetMaxOrd");
  check(CVodeSetNonlinConvCoef(mem, s.nonlin_conv_coef), "CVodeSetNonlinConvCoef");
  check(CVodeSetMaxNonlinIters(mem, s.max_nonlin_iters), "CVodeSetMaxNonlinIters");
  check(CVodeSetStabLimDet(mem, s.stab_lim_det ? SUNTRUE : SUNFALSE), "CVodeSetStabLimDet");
  check(CVodeSetLSetupFrequency(mem, s.lsetup_frequency), "CVodeSetLSetupFrequency");
  check(CVodeSetJacEvalFrequency(mem, s.jac_eval_frequency), "CVodeSetJacEvalFrequency");
}

}  // namespace

namespace {

class CvodeIntegrator final : public Integrator {
 public:
  CvodeIntegrator(const std::string& name, const OdeSystem& sys, const Tolerances& tol, const CvodeSettings& settings)
      : name_(name), problem_(*sys.problem), linear_(sys.linear), tol_(tol), settings_(settings),
        analytic_(name == "cvode") {
    if (!linear_)
      throw std::invalid_argument("integrator: " + name + " needs a linear solver with a sparse Jacobian; the system has none");
    ses_.problem = sys.problem;
    ses_.linear = sys.linear;
    if (SUNContext_Create(nullptr, &cv_.ctx) != 0) throw std::runtime_error("cvode: cannot create a SUNDIALS context");
    const int n = problem_.size();
    cv_.y = N_VNew_Serial(n, cv_.ctx);
    cv_.abstol = N_VNew_Serial(n, cv_.ctx);
    cv_.dky = N_VNew_Serial(n, cv_.ctx);
    const double atol = tol.absolute();
    for (int k = 0; k < n; ++k) N_VGetArrayPointer(cv_.abstol)[k] = atol * problem_.atol_scale(k);
  }
  std::string name() const override { return name_; }

  void start(double t, const Eigen::VectorXd& y) override {
    const int n = problem_.size();
    if (const std::string bad = problem_.check(t, y.data()); !bad.empty())
      throw DivergenceError(t, "at t = " + rounded_text(t, 9) + " s, " + bad);
    y_ = y_prev_ = y;
    t_ = t_prev_ = t;
    std::copy(y.data(), y.data() + n, N_VGetArrayPointer(cv_.y));
    tstop_ = std::nan("");
    window_steps_ = 0, window_t0_ = t, restart_ = false, since_restart_ = 0, root_returned_ = false;
    if (cv_.mem) {
      // restart: the law may jump here, and a multistep history across it is wrong
      add_counters(cv_.mem, ses_.done);
      check(CVodeReInit(cv_.mem, t, cv_.y), "CVodeReInit");
      return;
    }
    cv_.mem = CVodeCreate(CV_BDF, cv_.ctx);
    if (!cv_.mem) throw std::runtime_error("cvode: CVodeCreate failed");
    check(CVodeInit(cv_.mem, rhs_cb, t, cv_.y), "CVodeInit");
    check(CVodeSetUserData(cv_.mem, &ses_), "CVodeSetUserData");
    check(CVodeSetErrHandlerFn(cv_.mem, err_cb, &ses_), "CVodeSetErrHandlerFn");
    if (settings_.resolve > 0) {
      ses_.rtol = tol_.rtol;
      ses_.atol.assign(N_VGetArrayPointer(cv_.abstol), N_VGetArrayPointer(cv_.abstol) + n);
      ses_.cap.resize(n);
      for (int k = 0; k < n; ++k) ses_.cap[k] = settings_.resolve * problem_.resolution(k);
      check(CVodeWFtolerances(cv_.mem, weights_cb), "CVodeWFtolerances");
    } else {
      check(CVodeSVtolerances(cv_.mem, tol_.rtol, cv_.abstol), "CVodeSVtolerances");
    }
    check(CVodeSetMaxNumSteps(cv_.mem, -1), "CVodeSetMaxNumSteps");  // no limit: the caller's stop flag ends a run
    // the pattern (both variants) from the analytic Jacobian: the same for every state
    if (!linear_->sparse_jacobian(t, y.data(), ses_.J)) throw std::runtime_error("cvode: the linear solver gives no sparse Jacobian");
    ses_.J.makeCompressed();
    cv_.A = SUNSparseMatrix(n, n, ses_.J.nonZeros(), CSC_MAT, cv_.ctx);
    cv_.LS = SUNLinSol_KLU(cv_.y, cv_.A, cv_.ctx);
    if (!cv_.A || !cv_.LS) throw std::runtime_error("cvode: cannot create the linear solver");
    check(CVodeSetLinearSolver(cv_.mem, cv_.LS, cv_.A), "CVodeSetLinearSolver");
    if (analytic_) {
      check(CVodeSetJacFn(cv_.mem, jac_cb), "CVodeSetJacFn");
    } else {
      ses_.colouring = colour_columns(ses_.J);
      check(CVodeSetJacFn(cv_.mem, fd_jac_cb), "CVodeSetJacFn");
    }
    if (settings_.kink_gap > 0 && problem_.switch_count() > 0)
      check(CVodeRootInit(cv_.mem, problem_.switch_count(), switches_cb), "CVodeRootInit");
    apply(cv_.mem, settings_);
  }

  void step(double t_land) override {
    if (restart_) restart_ = false, start(t_, y_);
    if (!(tstop_ == t_land)) {
      check(CVodeSetStopTime(cv_.mem, t_land), "CVodeSetStopTime");
      tstop_ = t_land;
    }
    double t_ret = t_;
    long ncf_before = 0, ncf_after = 0;
    CVodeGetNumNonlinSolvConvFails(cv_.mem, &ncf_before);
    // in one-step mode tout only bounds CVODE's estimate of a first step: after the last event a
    // live simulation lands nowhere (t_land = inf), and an unbounded estimate was an infinite
    // step, F evaluated at t = inf and the run stopped (CV_REPTD_RHSFUNC_ERR)
    const double tout = std::isfinite(t_land) ? t_land : t_ + 1.0;
    int flag = CVode(cv_.mem, tout, cv_.y, &t_ret, CV_ONE_STEP);
    // after a kink it did not restart at (within kink_gap), CVODE first checks the switching
    // functions at the root it returned, and stops (CV_ILL_INPUT, "root found at and very near")
    // when one is exactly zero there and just after. Nothing has moved: restart at the root,
    // where CVODE sets such a function aside until it leaves zero, and take the step again.
    if (flag == CV_ILL_INPUT && root_returned_) {
      start(t_, y_);
      check(CVodeSetStopTime(cv_.mem, t_land), "CVodeSetStopTime");
      tstop_ = t_land;
      flag = CVode(cv_.mem, tout, cv_.y, &t_ret, CV_ONE_STEP);
    }
    root_returned_ = flag == CV_ROOT_RETURN;
    // convergence failures of this step, at the time it started from (CVODE gives no other)
    CVodeGetNumNonlinSolvConvFails(cv_.mem, &ncf_after);
    ses_.warnings.add(WarningKind::cvode_convergence, t_, ncf_after - ncf_before);
    if (ses_.error) std::rethrow_exception(std::exchange(ses_.error, nullptr));
    if (flag < 0)
      throw DivergenceError(t_, "cvode stopped at t = " + rounded_text(t_, 9) + " s: " + CVodeGetReturnFlagName(flag) +
                                    (ses_.last_error.empty() ? "" : " (" + ses_.last_error + ")") + "; " +
                                    absurd_input(t_ret) + largest_error());
    if (flag == CV_TSTOP_RETURN) t_ret = t_land, tstop_ = std::nan("");  // SUNDIALS 6 clears a reached stop time
    // a kink located: restart there (at the next step, as after a stall), unless the last
    // restart was fewer than kink_gap steps ago (CvodeSettings::kink_gap)
    ++since_restart_;
    if (flag == CV_ROOT_RETURN && since_restart_ >= settings_.kink_gap) restart_ = true, ++ses_.kink_restarts;
    // a step size at rounding level means CVODE cannot get on (it may creep towards a time
    // where F fails for ever): stop as the one-step integrators do
    double h_now = 0;
    CVodeGetCurrentStep(cv_.mem, &h_now);
    if (!(std::abs(h_now) >= 16 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_ret))))
      throw DivergenceError(t_ret, "cvode: the step size collapsed to " + rounded_text(h_now, 9) +
                                       " s at t = " + rounded_text(t_ret, 9) + " s" +
                                       (ses_.last_error.empty() ? "" : " (" + ses_.last_error + ")") + "; " +
                                       absurd_input(t_ret) + largest_error());
    const double* yr = N_VGetArrayPointer(cv_.y);
    if (const std::string bad = problem_.check(t_ret, yr); !bad.empty())
      throw DivergenceError(t_, diverged_text(t_, t_ret, bad));
    t_prev_ = t_, t_ = t_ret;
    y_prev_.swap(y_);
    y_.resize(problem_.size());
    std::copy(yr, yr + problem_.size(), y_.data());
    problem_.counters = work();  // the problem's counters tell the same as for the one-step methods
    // a stall: the BDF history (order, step, Jacobian age) that got it here cannot get it out;
    // a restart from the current state can (the reference implementation's CVODE run restarted too)
    if (settings_.stall_window > 0 && ++window_steps_ >= settings_.stall_window) {
      const bool stalled = t_ - window_t0_ < settings_.stall_window * settings_.stall_step;
      window_steps_ = 0, window_t0_ = t_;
      if (stalled) {
        ses_.warnings.add(WarningKind::cvode_restart, t_);
        restart_ = true;  // at the next step: the samples inside this one still need its history
      }
    }
  }

  // a known kink at t(): restart the BDF history there
  void kink() override { start(t_, y_); }

  // an applied input beyond the problem's scales at the last accepted state's time or at t (where
  // CVODE got to), "...; ", as the one-step methods name it (OdeProblem::absurd_input)
  std::string absurd_input(double t) const { return problem_.absurd_note(t_, t, y_.data()); }

  // "the largest error is in <component>" for the stop messages, as the one-step methods say it:
  // the component of the largest weighted local error estimate of CVODE's last attempt
  std::string largest_error() const {
    const int n = problem_.size();
    N_Vector ele = N_VClone(cv_.y), w = N_VClone(cv_.y);
    int worst = -1;
    if (ele && w && CVodeGetEstLocalErrors(cv_.mem, ele) == CV_SUCCESS && CVodeGetErrWeights(cv_.mem, w) == CV_SUCCESS) {
      const double *e = N_VGetArrayPointer(ele), *wt = N_VGetArrayPointer(w);
      double largest = 0;
      for (int k = 0; k < n; ++k)
        if (const double ek = std::abs(e[k] * wt[k]); std::isfinite(ek) && ek > largest) largest = ek, worst = k;
    }
    for (N_Vector v : {ele, w})
      if (v) N_VDestroy(v);
    return worst < 0 ? "no component has an error estimate" : "the largest error is in " + problem_.describe(worst);
  }

  void dense(double t, Eigen::VectorXd& out) const override {
    if (t >= t_) {
      out = y_;
      return;
    }
    check(CVodeGetDky(cv_.mem, std::max(t, t_prev_), 0, cv_.dky), "CVodeGetDky");
    const double* d = N_VGetArrayPointer(cv_.dky);
    out = Eigen::Map<const Eigen::VectorXd>(d, problem_.size());
  }

  WorkCounters work() const override {
    WorkCounters w = ses_.done;
    if (cv_.mem) add_counters(cv_.mem, w);
    w.warnings = ses_.warnings;
    w.rhs += ses_.fd_rhs;
    w.kink_restarts = ses_.kink_restarts;
    return w;
  }


 private:
  std::string name_;
  OdeProblem& problem_;
  LinearSolver* linear_;
  Tolerances tol_;
  CvodeSettings settings_;
  bool analytic_;
  Session ses_;
  Cvode cv_;
  double tstop_ = std::nan("");
  bool restart_ = false;   // a stall was seen or a kink located: restart before the next step
  long window_steps_ = 0;  // steps since the stall window began
  long since_restart_ = 0; // steps since the last (re)start
  bool root_returned_ = false;  // the last step ended at a located kink
  double window_t0_ = 0;   // [s] time the window began
};

}  // namespace

std::unique_ptr<Integrator> make_cvode_integrator(const std::string& name, const OdeSystem& sys, const Tolerances& tol,
                                                  const CvodeSettings& settings) {
  return std::make_unique<CvodeIntegrator>(name, sys, tol, settings);
}

DriveResult drive_cvode(const OdeSystem& sys, const std::string& name, const Tolerances& tol, const DriveOptions& opt,
                        Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress,
                        const CvodeSettings& settings) {
  check_tolerances(tol);
  CvodeIntegrator integ(name, sys, tol, settings);
  return drive(integ, opt, y, sample, progress);
}

std::string describe(const CvodeSettings& s) {
  std::ostringstream o;
  o << "order <= " << s.max_order << ", nonlinear coefficient " << s.nonlin_conv_coef << ", Newton iterations <= "
    << s.max_nonlin_iters << ", Jacobian every " << s.jac_eval_frequency << " steps, setup every "
    << s.lsetup_frequency << " steps, stability limit detection " << (s.stab_lim_det ? "on" : "off")
    << ", restart when " << s.stall_window << " steps advance less than " << s.stall_window * s.stall_step << " s";
  if (s.kink_gap > 0) o << ", restart at kinks " << s.kink_gap << " steps apart or more";
  if (s.resolve > 0) o << ", errors below " << s.resolve << " of the laws' resolution";
  return o.str();
}

}  // namespace beltsim
