// Helpers shared by the physics tests: run a scene and keep the samples.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "integrate/belt_system.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "scene/scene.hpp"

namespace beltsim::testing {

struct Samples {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y;
  DriveResult result;
};

inline Samples simulate(const Model& m, const Drive& dr, const Eigen::VectorXd& y0, double t_end, double sample_dt,
                        const char* method, double rtol) {
  BeltSystem sys(m, dr);
  auto stepper = make_stepper(method);
  DriveOptions opt;
  opt.t_end = t_end;
  opt.sample_dt = sample_dt;
  opt.events = dr.breakpoints();
  Samples s;
  Eigen::VectorXd y = y0;
  s.result = drive(sys, *stepper, Tolerances{rtol, -1}, opt, y, [&](double t, const Eigen::VectorXd& yy) {
    s.t.push_back(t);
    s.y.push_back(yy);
  });
  return s;
}

// the belt in rigid motion along its path at speed v [m/s] (positive along the direction of
// travel), pulleys turning with it
inline Eigen::VectorXd rigid_motion(const Scene& sc, double v) {
  const Model& m = sc.model;
  const int N = m.n_coord();
  Eigen::VectorXd y = sc.y0;
  const int n = m.n_el();
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, b = (i + 1) % n;
    Eigen::Vector2d d(y[3 * b] - y[3 * a], y[3 * b + 1] - y[3 * a + 1]);
    d.normalize();
    y[N + 3 * i] = v * d.x();
    y[N + 3 * i + 1] = v * d.y();
    // the element turns with the path: ω = v/ρ on an arc (the chord angle per pitch / time per pitch)
    const double turn = std::remainder(y[3 * b + 2] - y[3 * a + 2], 2 * M_PI) / 2;
    y[N + 3 * i + 2] = v * turn / m.belt.pitch;
  }
  for (size_t k = 0; k < sc.route_pulleys.size(); ++k) {
    const int j = sc.route_pulleys[k];
    y[N + m.pulley_coord(j)] = sc.route.arcs[k].sense * v / m.pulleys[j].radius;
  }
  return y;
}

}  // namespace beltsim::testing
