#include "integrate/driver.hpp"

#include <cmath>

#include "integrate/timeline.hpp"

namespace beltsim {

DriveResult drive(Integrator& integ, const DriveOptions& opt, Eigen::VectorXd& y, const SampleFn& sample,
                  const ProgressFn& progress) {
  Timeline tl(integ);
  double last_sample = -std::numeric_limits<double>::infinity();
  if (opt.sample_dt > 0)
    tl.add_stream(opt.t0, opt.sample_dt, [&](double t, const Eigen::VectorXd& yy) { last_sample = t, sample(t, yy); });
  for (const DriveOptions::Stream& s : opt.streams) tl.add_stream(s.t0, s.dt, s.fn);
  std::vector<Timeline::Landing> landings;
  for (double e : opt.events)
    if (e > opt.t0 && e < opt.t_end)
      landings.push_back({e, opt.on_event ? Timeline::Action([&](double t) {
                                              Eigen::VectorXd yy = tl.state();
                                              opt.on_event(t, yy);
                                              tl.changed(&yy);
                                            })
                                          : Timeline::Action()});
  landings.push_back({opt.t_end, {}});  // a run with an end lands on it
  tl.set_landings(std::move(landings));
  tl.start(opt.t0, y);
  const Timeline::Result r = tl.run_to(opt.t_end, opt.stop, progress);
  y = tl.state();
  if (opt.sample_dt > 0 && !r.interrupted && last_sample < opt.t_end - 1e-12 * std::max(1.0, std::abs(opt.t_end)))
    sample(r.t, y);
  DriveResult res;
  res.work = integ.work();
  res.t_reached = r.t;
  res.interrupted = r.interrupted;
  res.wall_seconds = r.wall;
  return res;
}

DriveResult drive(const OdeSystem& sys, Stepper& stepper, const Tolerances& tol, const DriveOptions& opt,
                  Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress) {
  auto integ = make_one_step(stepper, sys, tol, opt.h_max > 0 ? opt.h_max : opt.t_end - opt.t0);
  return drive(*integ, opt, y, sample, progress);
}

}  // namespace beltsim
