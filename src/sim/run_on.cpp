#include "sim/run_on.hpp"

#include "integrate/belt_system.hpp"
#include "integrate/stepper.hpp"

namespace beltsim {

namespace {

void run(const Model& m, const Drive& d, double t0, const Eigen::VectorXd& y0, double window, double rtol,
         DriveOptions& opt, const SampleFn& sample) {
  BeltSystem sys(m, d);
  auto stepper = make_stepper("esdirk32");
  opt.t0 = t0;
  opt.t_end = t0 + window;
  opt.events = d.breakpoints();
  Eigen::VectorXd state = y0;
  drive(sys, *stepper, Tolerances{rtol, Tolerances::kAtolUnset}, opt, state, sample);
}

}  // namespace

void run_on(const Model& m, const Drive& d, double t0, const Eigen::VectorXd& y0, double window, double dt, double rtol,
            const SampleFn& sample) {
  DriveOptions opt;
  opt.sample_dt = dt;
  run(m, d, t0, y0, window, rtol, opt, sample);
}

void run_on(const Model& m, const Drive& d, double t0, const Eigen::VectorXd& y0, double window, double rtol,
            std::vector<DriveOptions::Stream> grids) {
  DriveOptions opt;
  opt.sample_dt = 0;
  opt.streams = std::move(grids);
  run(m, d, t0, y0, window, rtol, opt, {});
}

}  // namespace beltsim
