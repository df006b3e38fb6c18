#include "integrate/cvode.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <Eigen/SparseCore>

#include "integrate/controller.hpp"

namespace beltsim {

std::vector<std::string> cvode_names() { return {"cvode", "cvode-fd"}; }
bool is_cvode(const std::string& name) { return name == "cvode" || name == "cvode-fd"; }

namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

struct Session {
  OdeSystem* sys = nullptr;
  Eigen::SparseMatrix<double> J;  // analytic Jacobian, CSC
  std::string last_error;
  WorkCounters done;              // counters of the finished segments (CVodeReInit resets CVODE's)
};

int rhs_cb(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  Session& s = *static_cast<Session*>(user);
  const double* yy = N_VGetArrayPointer(y);
  double* dy = N_VGetArrayPointer(ydot);
  s.sys->rhs(t, yy, dy);
  for (int k = 0, n = s.sys->size(); k < n; ++k)
    if (!std::isfinite(dy[k])) return 1;  // recoverable: CVODE retries with a smaller step
  return 0;
}

// J = ∂F/∂y from the system, copied into CVODE's CSC matrix (same pattern every call)
int jac_cb(sunrealtype t, N_Vector y, N_Vector, SUNMatrix A, void* user, N_Vector, N_Vector, N_Vector) {
  Session& s = *static_cast<Session*>(user);
  if (!s.sys->sparse_jacobian(t, N_VGetArrayPointer(y), s.J)) return -1;
  s.J.makeCompressed();
  const sunindextype nnz = s.J.nonZeros();
  if (SUNSparseMatrix_NNZ(A) < nnz && SUNSparseMatrix_Reallocate(A, nnz) != 0) return -1;
  sunindextype* ptr = SUNSparseMatrix_IndexPointers(A);
  sunindextype* idx = SUNSparseMatrix_IndexValues(A);
  double* val = SUNSparseMatrix_Data(A);
  for (Eigen::Index c = 0; c <= s.J.outerSize(); ++c) ptr[c] = s.J.outerIndexPtr()[c];
  for (sunindextype k = 0; k < nnz; ++k) idx[k] = s.J.innerIndexPtr()[k], val[k] = s.J.valuePtr()[k];
  return 0;
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

}  // namespace

DriveResult drive_cvode(OdeSystem& sys, const std::string& name, const Tolerances& tol, const DriveOptions& opt,
                        Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const int n = sys.size();
  const bool analytic = name == "cvode";
  Session ses;
  ses.sys = &sys;
  Cvode cv;
  if (SUNContext_Create(nullptr, &cv.ctx) != 0) throw std::runtime_error("cvode: cannot create a SUNDIALS context");
  cv.y = N_VNew_Serial(n, cv.ctx);
  cv.abstol = N_VNew_Serial(n, cv.ctx);
  cv.dky = N_VNew_Serial(n, cv.ctx);
  std::copy(y.data(), y.data() + n, N_VGetArrayPointer(cv.y));
  const double atol = tol.atol < 0 ? tol.rtol : tol.atol;
  for (int k = 0; k < n; ++k) N_VGetArrayPointer(cv.abstol)[k] = atol * sys.atol_scale(k);

  cv.mem = CVodeCreate(CV_BDF, cv.ctx);
  if (!cv.mem) throw std::runtime_error("cvode: CVodeCreate failed");
  check(CVodeInit(cv.mem, rhs_cb, opt.t0, cv.y), "CVodeInit");
  check(CVodeSetUserData(cv.mem, &ses), "CVodeSetUserData");
  check(CVodeSetErrHandlerFn(cv.mem, err_cb, &ses), "CVodeSetErrHandlerFn");
  check(CVodeSVtolerances(cv.mem, tol.rtol, cv.abstol), "CVodeSVtolerances");
  check(CVodeSetMaxNumSteps(cv.mem, -1), "CVodeSetMaxNumSteps");  // no limit: the caller's stop flag ends a run
  if (analytic) {
    if (!sys.sparse_jacobian(opt.t0, y.data(), ses.J)) throw std::runtime_error("cvode: the system has no sparse Jacobian");
    ses.J.makeCompressed();
    cv.A = SUNSparseMatrix(n, n, ses.J.nonZeros(), CSC_MAT, cv.ctx);
    cv.LS = SUNLinSol_KLU(cv.y, cv.A, cv.ctx);
  } else {
    cv.A = SUNDenseMatrix(n, n, cv.ctx);
    cv.LS = SUNLinSol_Dense(cv.y, cv.A, cv.ctx);
  }
  if (!cv.A || !cv.LS) throw std::runtime_error("cvode: cannot create the linear solver");
  check(CVodeSetLinearSolver(cv.mem, cv.LS, cv.A), "CVodeSetLinearSolver");
  if (analytic) check(CVodeSetJacFn(cv.mem, jac_cb), "CVodeSetJacFn");

  // sample times t0 + k·dt and t_end, as drive()
  const double span = opt.t_end - opt.t0;
  const long n_samples = opt.sample_dt > 0 ? static_cast<long>(std::floor(span / opt.sample_dt * (1 + 1e-12))) : 0;
  auto sample_time = [&](long k) { return k > n_samples ? opt.t_end : opt.t0 + static_cast<double>(k) * opt.sample_dt; };
  const long last_sample = sample_time(n_samples) < opt.t_end - 1e-12 * span ? n_samples + 1 : n_samples;
  long next_sample = 0;
  std::vector<double> events;
  for (double e : opt.events)
    if (e > opt.t0 && e < opt.t_end) events.push_back(e);
  std::sort(events.begin(), events.end());
  events.erase(std::unique(events.begin(), events.end()), events.end());
  events.push_back(opt.t_end);

  if (const std::string bad = sys.check(opt.t0, y.data()); !bad.empty())
    throw DivergenceError(opt.t0, "initial state at t = " + fmt(opt.t0) + " s: " + bad);
  sample(opt.t0, y), next_sample = 1;
  // frames: frame_t0 + k·frame_dt up to t_end, from the same interpolation (as drive())
  const bool frames = opt.frame && opt.frame_dt > 0;
  long next_frame = 0;
  auto frame_time = [&](long k) { return opt.frame_t0 + static_cast<double>(k) * opt.frame_dt; };
  if (frames)
    while (frame_time(next_frame) < opt.t0 - 1e-12 * span) next_frame++;
  if (frames && std::abs(frame_time(next_frame) - opt.t0) <= 1e-12 * span) opt.frame(frame_time(next_frame), y), next_frame++;

  DriveResult res;
  double t = opt.t0;
  Eigen::VectorXd dense(n);
  auto finish = [&] {
    WorkCounters w = ses.done;
    add_counters(cv.mem, w);
    sys.counters = w;
    res.work = w;
    res.t_reached = t;
    res.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  };
  for (size_t e = 0; e < events.size() && !res.interrupted; ++e) {
    const double t_event = events[e];
    check(CVodeSetStopTime(cv.mem, t_event), "CVodeSetStopTime");
    while (t < t_event) {
      if (opt.stop && opt.stop->load()) {
        res.interrupted = true;
        break;
      }
      double t_ret = t;
      const int flag = CVode(cv.mem, t_event, cv.y, &t_ret, CV_ONE_STEP);
      if (flag < 0) {
        finish();
        throw DivergenceError(t, "cvode stopped at t = " + fmt(t) + " s: " + CVodeGetReturnFlagName(flag) +
                                     (ses.last_error.empty() ? "" : " (" + ses.last_error + ")"));
      }
      if (flag == CV_TSTOP_RETURN) t_ret = t_event;
      // a step size at rounding level means CVODE cannot get on (it may creep towards a time
      // where F fails for ever): stop as drive() does
      double h_now = 0;
      CVodeGetCurrentStep(cv.mem, &h_now);
      if (std::abs(h_now) < 16 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_ret))) {
        finish();
        throw DivergenceError(t_ret, "cvode: the step size collapsed to " + fmt(h_now) + " s at t = " + fmt(t_ret) +
                                         " s" + (ses.last_error.empty() ? "" : " (" + ses.last_error + ")"));
      }
      const double* yr = N_VGetArrayPointer(cv.y);
      if (const std::string bad = sys.check(t_ret, yr); !bad.empty()) {
        finish();
        throw DivergenceError(t_ret, "the run diverged at t = " + fmt(t_ret) + " s: " + bad);
      }
      while (next_sample <= last_sample && sample_time(next_sample) <= t_ret + 1e-12 * span) {
        const double ts = std::min(sample_time(next_sample), t_ret);
        if (ts >= t_ret) {
          std::copy(yr, yr + n, dense.data());
        } else {
          check(CVodeGetDky(cv.mem, ts, 0, cv.dky), "CVodeGetDky");
          std::copy(N_VGetArrayPointer(cv.dky), N_VGetArrayPointer(cv.dky) + n, dense.data());
        }
        sample(ts, dense);
        next_sample++;
      }
      while (frames && frame_time(next_frame) <= std::min(t_ret, opt.t_end) + 1e-12 * span) {
        const double tf = std::min(frame_time(next_frame), opt.t_end);
        check(CVodeGetDky(cv.mem, std::min(tf, t_ret), 0, cv.dky), "CVodeGetDky");
        std::copy(N_VGetArrayPointer(cv.dky), N_VGetArrayPointer(cv.dky) + n, dense.data());
        opt.frame(tf, dense);
        next_frame++;
      }
      t = t_ret;
      if (progress) {
        WorkCounters w = ses.done;
        add_counters(cv.mem, w);
        progress(t, w);
      }
    }
    if (res.interrupted || t >= opt.t_end) break;
    // restart at the event: the law may jump there, and a multistep history across it is wrong
    std::copy(N_VGetArrayPointer(cv.y), N_VGetArrayPointer(cv.y) + n, y.data());
    if (opt.on_event) opt.on_event(t, y);
    std::copy(y.data(), y.data() + n, N_VGetArrayPointer(cv.y));
    add_counters(cv.mem, ses.done);
    check(CVodeReInit(cv.mem, t, cv.y), "CVodeReInit");
  }
  std::copy(N_VGetArrayPointer(cv.y), N_VGetArrayPointer(cv.y) + n, y.data());
  finish();
  return res;
}

}  // namespace beltsim
