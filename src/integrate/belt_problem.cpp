#include "integrate/belt_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "integrate/switches.hpp"
#include "model/forces.hpp"

namespace beltsim {

BeltProblem::BeltProblem(const Model& m, const Drive& d) : model_(m), drive_(d), ws_(m) {}

double BeltProblem::atol_scale(int k) const {
  // natural sizes (kNaturalSizes): 0.1 m (layout), 1 rad, 1 m/s, 10 rad/s (element spin), 1 rad/s
  // (pulley speed), 1 J, and a bristle's deflection at μ = 1, 1/σ0 (so that its error weighs as μ's)
  const int N = model_.n_coord(), ne = 3 * model_.n_el();
  if (k >= model_.bristle_offset()) {
    const Friction& f = model_.friction_of(k - model_.bristle_offset());
    return f.law == FrictionKind::lugre ? 1.0 / f.bristle_stiffness : 1.0;  // z stays 0 under another law
  }
  if (k >= 2 * N) return 1.0;
  const bool vel = k >= N;
  const int c = vel ? k - N : k;
  if (c >= ne) return 1.0;  // pulley angle [rad], speed [rad/s]
  if (c % 3 == 2) return vel ? 10.0 : 1.0;
  return vel ? 1.0 : 0.1;
}

bool BeltProblem::in_state_norm(int k) const {
  const int N = model_.n_coord(), ne = 3 * model_.n_el();
  return !(k >= N && k < N + ne);
}

bool BeltProblem::held_each(int k) const {
  return k >= model_.bristle_offset() && model_.friction_of(k - model_.bristle_offset()).law == FrictionKind::lugre;
}

double BeltProblem::resolution(int k) const {
  // an element's velocity (x, y) and a pulley's surface speed: the friction band Δv
  const int N = model_.n_coord(), ne = 3 * model_.n_el();
  if (k < N || k >= 2 * N) return std::numeric_limits<double>::infinity();
  const int c = k - N;
  if (c < ne) return c % 3 == 2 ? std::numeric_limits<double>::infinity() : model_.friction_of(c / 3).dv;
  double band = model_.friction.dv;  // a pulley's speed: the narrowest band on the belt
  for (const Friction& f : model_.laws) band = std::min(band, f.dv);
  return band / model_.pulleys[c - ne].radius;
}

int BeltProblem::switch_count() const { return beltsim::switch_count(model_); }

void BeltProblem::switches(double t, const double* y, double* g) {
  contact_switches(model_, contacts_at(model_, drive_, t, y, ws_, Pairs::all).pairs(), g);
}

std::string BeltProblem::describe(int k) const {
  static const char* elem_q[] = {"x position", "y position", "angle"};
  static const char* elem_v[] = {"x velocity", "y velocity", "angular velocity"};
  static const char* energy[] = {"work of the torques", "SDE axial dissipation", "SDE bending dissipation",
                                 "contact dissipation", "friction dissipation"};
  const int N = model_.n_coord(), ne = 3 * model_.n_el();
  std::ostringstream s;
  if (k >= model_.bristle_offset()) {
    s << "element " << k - model_.bristle_offset() << " bristle deflection";
    return s.str();
  }
  if (k >= 2 * N) {
    s << "energy integral (" << energy[k - 2 * N] << ")";
    return s.str();
  }
  const bool vel = k >= N;
  const int c = vel ? k - N : k;
  if (c < ne)
    s << "element " << c / 3 << ' ' << (vel ? elem_v : elem_q)[c % 3];
  else if (c < ne + model_.n_p())
    s << "pulley '" << model_.pulleys[c - ne].name << "' " << (vel ? "speed" : "angle");
  else if (c < ne + model_.n_p() + model_.n_arm())
    s << "pulley '" << model_.pulleys[model_.arms[c - ne - model_.n_p()].pulley].name << "' tensioner arm "
      << (vel ? "rate" : "angle");
  else
    for (int r = 0; r < model_.n_coupling(); ++r) {
      const bool hub = c == model_.rotor_coord(r) + 1 && model_.couplings[r].one_way;
      if (c == model_.rotor_coord(r) || hub)
        s << "pulley '" << model_.pulleys[model_.couplings[r].pulley].name << "' " << (hub ? "clutch hub " : "rotor ")
          << (vel ? "speed" : "angle");
    }
  return s.str();
}

std::string BeltProblem::absurd_input(double t, const double* y) const {
  const double force = model_.belt.k * std::pow(model_.belt.rigid_length, model_.belt.e_tra);  // [N]: EA
  const double* v = y + model_.n_coord();
  int worst = -1;
  double worst_share = kAbsurdTorque, worst_torque = 0;
  for (int j = 0; j < model_.n_p(); ++j) {
    if (drive_.kinematic(j)) continue;
    double M = 0;
    try {
      M = applied_torque(model_, drive_, t, v, j);
    } catch (const std::exception&) {  // (a Lua law that fails here fails the run on its own)
      continue;
    }
    const double limit = force * model_.pulleys[j].radius;
    if (const double share = std::abs(M) / limit; !std::isfinite(M) || share > worst_share)
      worst = j, worst_share = std::isfinite(M) ? share : INFINITY, worst_torque = M;
  }
  if (worst < 0) return {};
  const double r = model_.pulleys[worst].radius;
  std::ostringstream m;
  m << "pulley '" << model_.pulleys[worst].name << "'.torque = " << worst_torque << " N·m at t = " << t
    << " s is beyond any torque its belt could carry (" << force * r
    << " N·m: the axial force that stretches the belt by its own length, " << force << " N, at its radius " << r
    << " m); check its law";
  return m.str();
}

std::string BeltProblem::check(double, const double* y) const {
  const int N = model_.n_coord();
  const int n = model_.n_state();
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(y[k])) return describe(k) + " is " + (std::isnan(y[k]) ? "NaN" : "infinite");
  // runaway: a belt element more than 100 pitches away from every pulley's contact circle or
  // moving faster than 1 km/s, a pulley faster than kPulleySpeedMax
  double reach = 0;
  for (const Pulley& p : model_.pulleys) reach = std::max(reach, p.centre.norm() + p.radius);
  reach += 100 * model_.belt.pitch;
  // (squares against squares: the state is finite here, and this runs after every step)
  for (int i = 0; i < model_.n_el(); ++i) {
    const double x = y[3 * i], yy = y[3 * i + 1], vx = y[N + 3 * i], vy = y[N + 3 * i + 1];
    if (x * x + yy * yy > reach * reach) {
      std::ostringstream s;
      s << "element " << i << " flew off to (" << x << ", " << yy << ") m";
      return s.str();
    }
    if (vx * vx + vy * vy > 1e6) {
      std::ostringstream s;
      s << "element " << i << " runs away at " << std::hypot(vx, vy) << " m/s";
      return s.str();
    }
  }
  for (int j = 0; j < model_.n_p(); ++j) {
    const double w = y[N + model_.pulley_coord(j)];
    if (std::abs(w) > kPulleySpeedMax) {
      std::ostringstream s;
      // a prescribed speed does not run away: its law asks for it (a user's trial: a step to -1e6)
      if (drive_.kinematic(j))
        s << "pulley '" << model_.pulleys[j].name << "'.speed is " << w << " rad/s, beyond the " << kPulleySpeedMax
          << " rad/s a run allows (its law prescribes it: check the law)";
      else
        s << "pulley '" << model_.pulleys[j].name << "' runs away at " << w << " rad/s";
      return s.str();
    }
  }
  return {};
}

}  // namespace beltsim

namespace beltsim {

int BeltProblem::answer_size() const {
  return model_.n_p() + model_.n_arm() + model_.n_coupling() + static_cast<int>(spans_.size());
}

int BeltProblem::head() const {
  return model_.n_p() + model_.n_arm() + model_.n_coupling();
}

int BeltProblem::span_sdes(const double* y, int count) {
  const int ns = std::max(0, count - head());
  nearest_.resize(static_cast<size_t>(ns));
  if (ns > 0) sde_nearest(model_, y, spans_.data(), ns, nearest_.data());
  return ns;
}

void BeltProblem::answer(double, const double* y, double* a, int count) {
  const int N = model_.n_coord();
  double* const end = a + std::min(count, head());
  for (int j = 0; j < model_.n_p() && a < end; ++j) *a++ = y[N + model_.pulley_coord(j)];
  for (int r = 0; r < model_.n_arm() && a < end; ++r) *a++ = y[model_.arm_coord(r)];
  for (int c = 0; c < model_.n_coupling() && a < end; ++c) *a++ = y[N + model_.rotor_coord(c)];
  const int ns = span_sdes(y, count);
  for (int k = 0; k < ns; ++k) *a++ = sde_axial_force(model_, y, y + N, nearest_[k]);
}

void BeltProblem::answer_error(double, const double* y, const double* e, double* da, int count) {
  const int N = model_.n_coord();
  double* const end = da + std::min(count, head());
  for (int j = 0; j < model_.n_p() && da < end; ++j) *da++ = e[N + model_.pulley_coord(j)];
  for (int r = 0; r < model_.n_arm() && da < end; ++r) *da++ = e[model_.arm_coord(r)];
  for (int c = 0; c < model_.n_coupling() && da < end; ++c) *da++ = e[N + model_.rotor_coord(c)];
  const int ns = span_sdes(y, count);
  if (ns == 0) return;
  y_minus_e_.resize(static_cast<size_t>(2 * N));
  for (int k = 0; k < 2 * N; ++k) y_minus_e_[k] = y[k] - e[k];
  const double* z = y_minus_e_.data();
  for (int k = 0; k < ns; ++k) {
    const int i = nearest_[k];
    *da++ = sde_axial_force(model_, y, y + N, i) - sde_axial_force(model_, z, z + N, i);
  }
}

double BeltProblem::answer_scale(int k) const {
  // natural sizes: 1 rad/s (speeds), 1 rad (arm angles), 100 N (span tensions: a fifth of a
  // typical pretension, so that rtol·T decides for a span under load)
  const int speeds = model_.n_p() + model_.n_arm() + model_.n_coupling();
  return k < speeds ? 1.0 : 100.0;
}

bool BeltProblem::checked_inside(int k) const {
  return k < model_.n_p() + model_.n_arm() + model_.n_coupling();
}

std::string BeltProblem::describe_answer(int k) const {
  const int np = model_.n_p(), na = model_.n_arm(), nc = model_.n_coupling();
  if (k < np) return "pulley '" + model_.pulleys[k].name + "' speed";
  if (k < np + na) return "pulley '" + model_.pulleys[model_.arms[k - np].pulley].name + "' tensioner arm angle";
  if (k < np + na + nc) return "pulley '" + model_.pulleys[model_.couplings[k - np - na].pulley].name + "' rotor speed";
  return "span " + std::to_string(k - np - na - nc) + " tension";
}

}  // namespace beltsim
