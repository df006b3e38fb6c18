// Interval means of the time series: a force sampled at an instant aliases the element-passing
// frequency; its mean over the sample interval [t_{k-1}, t_k] does not. Averaged: each pulley's
// torque and belt torque, each route span's tension (at a free pulley I·dΩ/dt = M + M_belt, so
// over an interval mean(M) + mean(M_belt) = I·ΔΩ/Δt to the integrator's accuracy: tested).
//
// The mean is integrated over the integrator's accepted steps: in a step [a, b] each quantity is
// the straight line between its step-end values (exactly what blend_contact shows inside the
// step), so over [c, d] ⊂ [a, b]
//   ∫_c^d f dt = (d − c)·(f(c) + f(d))/2,   f(τ) = f_a + (τ − a)/(b − a)·(f_b − f_a)
// (the trapezoid rule on the step-end values). The accumulator holds ∫ from the interval's start
// to `covered` (inside the held step); cover() moves it on before the step is replaced (a new step
// or a restart) and a sample reads the means, then starts the next interval.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "model/drive.hpp"
#include "model/model.hpp"
#include "model/observables.hpp"
#include "scene/route.hpp"

namespace beltsim {

class Integrator;

class IntervalMeans {
 public:
  // the quantities of model m driven by drive along route, in the held step of integ (all read as
  // they are at each call)
  IntervalMeans(const Model& m, const Drive& drive, const Route& route, const Integrator& integ);

  // values per quantity: pulley j's torque at 2j and belt torque at 2j + 1, then span k's tension
  // at 2·n_p + k
  size_t size() const { return acc_.size(); }
  // the means from the interval's start to t (in the held step); NaN when t is the start.
  // serial counts the changes of the model or drive: a step end observed before one is observed again
  std::vector<double> means_to(double t, long serial) const;
  // the integral up to t (of the held step, before it is replaced)
  void cover(double t, long serial);
  // the next interval starts at t
  void start(double t);

  // its state (a run's state, sim/sim_state.hpp): the integral so far, the interval's start and
  // how far the integral reaches (the caller checks that it fits: size(), from <= covered <= now)
  struct State {
    std::vector<double> integral;
    double from = 0, covered = 0;  // [s]
  };
  State get_state() const { return {acc_, from_, covered_}; }
  void set_state(const State& s);

 private:
  struct StepEnd {
    std::vector<double> v;
    ContactRecords contacts;  // the step end's contact records (observe_pulleys)
    std::vector<PulleyObs> pulleys;
    double t = -1;
    long serial = -1;
  };
  const std::vector<double>& values(StepEnd& c, double t, const Eigen::VectorXd& y, long serial) const;
  std::vector<double> integral_to(double t, long serial) const;

  const Model& model_;
  const Drive& drive_;
  const Route& route_;
  const Integrator& integ_;
  mutable StepEnd a_, b_;  // the held step's two ends
  std::vector<double> acc_;
  double from_ = 0, covered_ = 0;
};

}  // namespace beltsim
