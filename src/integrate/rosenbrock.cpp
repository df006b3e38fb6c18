// Linearly implicit Rosenbrock(-W) stepper: per step one Jacobian, one factorisation of
// (I/(h·γ) - J) and one solve per stage, no Newton iterations, so a kink of the right-hand side
// (contact onset, stick/slip) costs at most a rejected step and the method restarts at once.
// L-stable: the stiff modes (friction in stick ≈ 5e9 1/s) are damped, not resolved.
#include <cmath>

#include "integrate/stepper.hpp"
#include "integrate/tableau.hpp"

namespace beltsim {

namespace {

class Rosenbrock final : public Stepper {
 public:
  Rosenbrock(std::string name, const RosenbrockTableau& tab) : name_(std::move(name)), tab_(tab) {}
  std::string name() const override { return name_; }
  int order() const override { return 3; }
  bool l_stable() const override { return true; }
  int embedded_order() const override { return 2; }

  bool needs_linear_solver() const override { return true; }

  bool step(const OdeSystem& sys, double t, const Eigen::VectorXd& y, const Eigen::VectorXd& f0, double h,
            Eigen::VectorXd& y1, Eigen::VectorXd& err) override {
    const int n = static_cast<int>(y.size());
    const int s = tab_.stages;
    if (!sys.linear->prepare_jacobian(t, y.data())) return false;
    sys.problem->counters.jacobians++;
    if (!sys.linear->factor(1.0 / (h * tab_.gamma))) return false;
    sys.problem->counters.factorizations++;
    ft_.setZero(n);
    sys.linear->time_derivative(ft_.data());
    u_.resize(s);
    for (int i = 0; i < s; ++i) {
      // right-hand side of stage i
      if (i == 0) {
        rhs_ = f0;
      } else {
        stage_ = y;
        for (int j = 0; j < i; ++j)
          if (tab_.a[i][j] != 0.0) stage_ += tab_.a[i][j] * u_[j];
        rhs_.resize(n);
        sys.problem->rhs(t + tab_.alpha_sum[i] * h, stage_.data(), rhs_.data());
        sys.problem->counters.rhs++;
        for (int j = 0; j < i; ++j) rhs_ += (tab_.c[i][j] / h) * u_[j];
      }
      if (tab_.gamma_sum[i] != 0.0) rhs_ += (tab_.gamma_sum[i] * h) * ft_;
      u_[i].resize(n);
      sys.linear->solve(rhs_.data(), u_[i].data());
      sys.problem->counters.solves++;
    }
    y1 = y;
    err.setZero(n);
    for (int i = 0; i < s; ++i) {
      y1 += tab_.m[i] * u_[i];
      err += tab_.e[i] * u_[i];
    }
    return y1.allFinite();
  }

 private:
  std::string name_;
  const RosenbrockTableau& tab_;
  std::vector<Eigen::VectorXd> u_;
  Eigen::VectorXd stage_, rhs_, ft_;
};

}  // namespace

std::unique_ptr<Stepper> make_rosenbrock() { return std::make_unique<Rosenbrock>("ros34pw2", ros34pw2()); }

}  // namespace beltsim
