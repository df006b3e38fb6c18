// Runge–Kutta–Fehlberg 4(5), the paper's integrator: six stages, the 4th-order solution is
// propagated and the difference to the 5th-order one estimates its error. Explicit, so its steps
// are limited by stability to h ≲ 2.8/|λ_max| (≈ 1e-9 s on the paper's drive; docs/integration.md).
#include "integrate/stepper.hpp"
#include "integrate/tableau.hpp"

namespace beltsim {

namespace {

class Rkf45 final : public Stepper {
 public:
  std::string name() const override { return "rkf45"; }
  int order() const override { return 4; }
  int embedded_order() const override { return 5; }
  bool step(const OdeSystem& sys, double t, const Eigen::VectorXd& y, const Eigen::VectorXd& f0, double h,
            Eigen::VectorXd& y1, Eigen::VectorXd& err) override {
    const ExplicitTableau& tab = fehlberg45();
    const int s = static_cast<int>(tab.b.size());
    k_.resize(s);
    k_[0] = f0;
    for (int i = 1; i < s; ++i) {
      stage_ = y;
      for (int j = 0; j < i; ++j)
        if (tab.a[i][j] != 0.0) stage_ += (h * tab.a[i][j]) * k_[j];
      k_[i].resize(y.size());
      sys.problem->rhs(t + tab.c[i] * h, stage_.data(), k_[i].data());
      sys.problem->counters.rhs++;
    }
    y1 = y;
    err.setZero(y.size());
    for (int i = 0; i < s; ++i) {
      y1 += (h * tab.b[i]) * k_[i];
      err += (h * (tab.b[i] - tab.b_hat[i])) * k_[i];
    }
    return true;
  }

 private:
  std::vector<Eigen::VectorXd> k_;
  Eigen::VectorXd stage_;
};

}  // namespace

std::unique_ptr<Stepper> make_rkf45() { return std::make_unique<Rkf45>(); }

}  // namespace beltsim
