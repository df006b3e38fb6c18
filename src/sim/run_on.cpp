#include "sim/run_on.hpp"

#include "integrate/belt_system.hpp"
#include "integrate/stepper.hpp"

namespace beltsim {

void run_on(const Model& m, const Drive& d, double t0, const Eigen::VectorXd& y0, double window, double dt, double rtol,
            const SampleFn& sample) {
  BeltSystem sys(m, d);
  auto stepper = make_stepper("esdirk32");
  DriveOptions opt;
  opt.t0 = t0;
  opt.t_end = t0 + window;
  opt.sample_dt = dt;
  opt.events = d.breakpoints();
  Eigen::VectorXd state = y0;
  drive(sys, *stepper, Tolerances{rtol, Tolerances::kAtolUnset}, opt, state, sample);
}

}  // namespace beltsim
