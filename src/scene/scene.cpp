// Scene builder: parameter validation, the belt's route, and the initial static state (DESIGN §3).
//
// Initial state. The elements' centres are placed on the route offset inwards by the static
// penetration p0_j on each pulley (c1·p0² + c2·p0 = N0 = 2·T0·sin(α/2), α the angle one pitch
// subtends), each rod along the path's tangent at its centre. Walking along the path, each
// centre is put where the gap of its SDE to the previous element is the one that carries the
// pretension, |d| = (T0/k)^(1/e_tra); the rigid length l_e is chosen (bisection) so that n
// elements close the loop exactly. This is an equilibrium on the spans and on the arcs, but not
// quite where a span meets an arc; a few Newton iterations on the elements' static equations
// (pulleys held, belt at rest, gravity on) remove the rest (f(q) = 0 with K = ∂f/∂q).
#include "scene/scene.hpp"

#include <tuple>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include <Eigen/SparseLU>

#include "integrate/warnings.hpp"
#include "model/forces.hpp"
#include "model/rhs.hpp"
#include "model/sparse.hpp"
#include "scene/validate.hpp"

namespace beltsim {

namespace {

std::string pulley_label(const PulleyDef& p) { return "pulley '" + p.name + "'"; }

double static_penetration(const Contact& c, double N0) {
  if (c.c1 > 0) return (-c.c2 + std::sqrt(c.c2 * c.c2 + 4 * c.c1 * N0)) / (2 * c.c1);
  return N0 / c.c2;
}

}  // namespace

void validate_law(const std::string& what, const TimeSpeedLaw& law, bool speed) {
  const std::string unit = speed ? "rad/s" : "N·m";
  require_finite(what + ".constant", law.constant, unit);
  require_finite(what + ".per_speed", law.per_speed, unit + "·s/rad");
  auto table = [&](const std::string& name, const std::vector<double>& x, const std::vector<double>& y,
                   const char* xunit) {
    if (x.size() != y.size()) throw ParameterError(what + "." + name + ": the two columns differ in length");
    for (size_t k = 0; k < x.size(); ++k) {
      require_finite(what + "." + name + " entry " + std::to_string(k + 1) + " (first)", x[k], xunit);
      require_finite(what + "." + name + " entry " + std::to_string(k + 1) + " (second)", y[k], unit);
      if (k > 0 && !(x[k] > x[k - 1]))
        reject(what + "." + name + " entry " + std::to_string(k + 1), "must be larger than the entry before it", x[k],
               xunit);
    }
  };
  table("table", law.t, law.value, "s");
  table("per_speed_table", law.omega, law.omega_value, "rad/s");
  for (const Ramp& r : law.ramps) {
    const std::string w = what + (r.is_step() ? " step" : " ramp");
    require_finite(w + ".t0", r.t0, "s");
    require_finite(w + ".t1", r.t1, "s");
    require_finite(w + ".from", r.from, unit);
    require_finite(w + ".to", r.to, unit);
    if (r.t1 < r.t0) reject(w + ".t1", "must not be before t0", r.t1, "s");
  }
  for (const Sine& s : law.sines) {
    require_finite(what + " sine.mean", s.mean, unit);
    require_finite(what + " sine.amplitude", s.amplitude, unit);
    require_non_negative(what + " sine.frequency", s.frequency, "Hz");
    require_finite(what + " sine.frequency", s.frequency, "Hz");
    require_finite(what + " sine.phase", s.phase, "rad");
  }
  for (const Harmonic& h : law.harmonics) {
    require_positive(what + " harmonics order", h.order, "");
    require_finite(what + " harmonics order", h.order, "");
    require_finite(what + " harmonics amplitude", h.amplitude, unit);
    require_finite(what + " harmonics phase", h.phase, "rad");
    require_finite(what + ".mean_speed", h.mean_speed, "rad/s");
  }
  if (speed && (law.per_speed != 0 || !law.omega.empty()))
    throw ParameterError(what + ": a prescribed speed cannot depend on the speed (per_speed, per_speed_table)");
}

void validate(const SceneDef& d) {
  if (d.pulleys.size() < 2)
    reject("scene", "needs at least 2 pulleys", static_cast<double>(d.pulleys.size()), "pulleys");
  std::set<std::string> names;
  for (const PulleyDef& p : d.pulleys) {
    if (p.name.empty()) throw ParameterError("every pulley needs a name");
    if (!names.insert(p.name).second) throw ParameterError("two pulleys are named '" + p.name + "'");
    const std::string w = pulley_label(p);
    require_finite(w + " centre x", p.centre.x(), "m");
    require_finite(w + " centre y", p.centre.y(), "m");
    require_positive(w + " radius", p.radius, "m");
    require_positive(w + " inertia", p.inertia, "kg·m²");
    if (p.kinematic) {
      validate_law(w + " speed", p.speed, true);
      if (!p.torque.is_zero()) throw ParameterError(w + ": give either a torque or a prescribed speed, not both");
    } else {
      validate_law(w + " torque", p.torque, false);
    }
  }
  for (size_t a = 0; a < d.pulleys.size(); ++a)
    for (size_t b = a + 1; b < d.pulleys.size(); ++b) {
      const PulleyDef &p = d.pulleys[a], &q = d.pulleys[b];
      const double dist = (p.centre - q.centre).norm();
      if (dist <= p.radius + q.radius) {
        std::ostringstream s;
        s << "pulleys '" << p.name << "' and '" << q.name << "' overlap: centres " << dist
          << " m apart, radii add up to " << p.radius + q.radius << " m";
        throw ParameterError(s.str());
      }
    }
  const BeltDef& b = d.belt;
  if (b.elements < 3) reject("belt.elements", "must be >= 3", b.elements, "");
  // the cost of a simulated second grows faster than the element count (README, Integration:
  // 2400 elements take about 10 min per simulated second); past this a scene is surely a mistake
  constexpr int kMaxElements = 20000;
  if (b.elements > kMaxElements && !d.allow_large) {
    std::ostringstream s;
    s << "belt.elements: " << b.elements << " elements are more than the limit of " << kMaxElements
      << " (about " << static_cast<long>(b.elements) * 2 / 1000 << " MB of state and Jacobian, and hours per simulated"
      << " second); set allow_large = true in the scene to go past";
    throw ParameterError(s.str());
  }
  switch (b.tensioning) {
    case Tensioning::pretension: require_positive("belt.pretension", b.pretension, "N"); break;
    case Tensioning::rest_length: require_positive("belt.rest_length", b.rest_length, "m"); break;
    case Tensioning::strain: require_positive("belt.strain", b.strain, ""); break;
  }
  if (b.loop_sense != 1 && b.loop_sense != -1) throw ParameterError("belt.direction must be 'cw' or 'ccw'");
  if (b.reading == StiffnessReading::rigidity) {
    require_positive("belt.EA", b.EA, "N");
    require_positive("belt.EI", b.EI, "N·m²");
    require_non_negative("belt.axial_damping", b.axial_damping, "N·s");
    require_non_negative("belt.bending_damping", b.bending_damping, "N·m·s/rad");
    if (b.bending_viscosity) require_non_negative("belt.bending_viscosity", *b.bending_viscosity, "N·m²·s");
  } else {
    if (b.bending_viscosity) throw ParameterError("belt.bending_viscosity: a rigidity; with per-SDE values (sde) give ct");
    require_positive("belt.sde.k", b.k, "N/m");
    require_positive("belt.sde.kt", b.kt, "N·m/rad");
    require_non_negative("belt.sde.c", b.c, "N·s/m");
    require_non_negative("belt.sde.ct", b.ct, "N·m·s/rad");
  }
  if (!(b.e_tra >= 1)) reject("belt.e_tra", "must be >= 1 (below 1 the stiffness is infinite at zero)", b.e_tra, "");
  if (!(b.e_tor >= 1)) reject("belt.e_tor", "must be >= 1 (below 1 the stiffness is infinite at zero)", b.e_tor, "");
  require_positive("belt.mass_per_length", b.mass_per_length, "kg/m");
  require_non_negative("belt.mu", b.mu, "");
  if (!b.mu_per_element.empty()) {
    if (static_cast<int>(b.mu_per_element.size()) != b.elements)
      reject("belt.mu per element", "needs one value per element", static_cast<double>(b.mu_per_element.size()),
             "values");
    for (double mu : b.mu_per_element) require_non_negative("belt.mu of an element", mu, "");
  }
  if (!b.route.empty()) {
    std::set<std::string> seen;
    for (const std::string& nm : b.route) {
      if (!names.count(nm)) throw ParameterError("belt.route names an unknown pulley '" + nm + "'");
      if (!seen.insert(nm).second) throw ParameterError("belt.route visits pulley '" + nm + "' twice");
    }
    if (seen.size() != names.size()) throw ParameterError("belt.route must visit every pulley once");
  }
  const ContactPerLength& cl = d.contact_per_length;
  if (cl.c1) require_non_negative("contact.c1_per_length", *cl.c1, "N/m³");
  else require_non_negative("contact.c1", d.contact.c1, "N/m²");
  if (cl.c2) require_positive("contact.c2_per_length", *cl.c2, "N/m²");
  else require_positive("contact.c2", d.contact.c2, "N/m");
  if (cl.b) require_non_negative("contact.damping_per_length", *cl.b, "N·s/m²");
  else require_non_negative("contact.damping", d.contact.b, "N·s/m");
  require_positive("contact.p_max", d.contact.p_max, "m");
  require_positive("friction.dv", d.friction.dv, "m/s");
  require_finite("gravity", d.gravity, "m/s²");
}

int Scene::find_pulley(const std::string& name) const {
  for (int j = 0; j < model.n_p(); ++j)
    if (model.pulleys[j].name == name) return j;
  return -1;
}

std::vector<int> Scene::senses() const {
  std::vector<int> s(model.n_p(), 1);
  for (size_t k = 0; k < route_pulleys.size(); ++k) s[route_pulleys[k]] = route.arcs[k].sense;
  return s;
}

int Scene::find_span(const std::string& a, const std::string& b) const {
  const size_t n = route_names.size();
  for (size_t k = 0; k < n; ++k) {
    const std::string& from = route_names[k];
    const std::string& to = route_names[(k + 1) % n];
    if ((from == a && to == b) || (from == b && to == a)) return static_cast<int>(k);
  }
  return -1;
}

int Scene::element_nearest(const Vec2& point) const {
  int best = 0;
  double bd = 1e300;
  for (int i = 0; i < model.n_el(); ++i) {
    const double dd = (Vec2(y0[3 * i], y0[3 * i + 1]) - point).squaredNorm();
    if (dd < bd) bd = dd, best = i;
  }
  return best;
}

namespace {

// place n element centres along `path`; returns where element n would go (= path.length when
// the loop closes). Rods lie along the path tangent; each SDE gap has the length `gap`.
double walk(const Route& path, int n, double h, double gap, std::vector<double>* s_out) {
  double s_prev = 0;
  if (s_out) s_out->assign(1, 0.0);
  Vec2 Cp, Tp, C, T;
  for (int i = 1; i <= n; ++i) {
    path.eval(s_prev, Cp, Tp);
    const Vec2 Bp = Cp + h * Tp;
    double lo = s_prev + h, hi = s_prev + 6 * h + 4 * gap;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      path.eval(mid, C, T);
      const Vec2 d = C - h * T - Bp;
      const double sigma = d.dot((T + Tp).normalized());
      (sigma < gap ? lo : hi) = mid;
    }
    s_prev = 0.5 * (lo + hi);
    if (s_out && i < n) s_out->push_back(s_prev);
  }
  return s_prev;
}

// Newton iterations on the elements' static equations; returns the final max |acceleration|.
// max_move > 0 limits how far one step may move any element centre (a trust region, used when
// the plain iteration went astray, see build_scene).
void poll_stop(const std::atomic<bool>* stop, int elements) {
  if (stop && stop->load(std::memory_order_relaxed))
    throw BuildInterrupted("scene: the build was interrupted while placing the belt and solving its static initial state (" +
                           std::to_string(elements) + " elements); no scene was made");
}

double static_solve(const Model& m, const Drive& d, Eigen::VectorXd& y, double max_move = 0,
                    const std::atomic<bool>* stop = nullptr) {
  const int ne = 3 * m.n_el();
  Eigen::VectorXd f(m.n_coord());
  Jacobian J;
  J.resize(m);
  Eigen::SparseMatrix<double> A;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  auto residual = [&](const Eigen::VectorXd& yy) {
    forces(m, d, 0.0, yy.data(), f.data());
    double r = 0;
    for (int k = 0; k < ne; ++k) r = std::max(r, std::abs(f[k] / m.mass_of(k)));
    return r;
  };
  double res = residual(y);
  for (int it = 0; it < 30 && res > 1e-9; ++it) {
    poll_stop(stop, m.n_el());
    jacobian(m, d, 0.0, y.data(), J);
    assemble(m, d, 0.0, 0.0, J.C, J.K, ne, A);  // A = -K_ee
    poll_stop(stop, m.n_el());
    lu.compute(A);
    poll_stop(stop, m.n_el());
    if (lu.info() != Eigen::Success) break;
    Eigen::VectorXd dq = lu.solve(f.head(ne));
    if (max_move > 0) {
      double big = 0;
      for (int i = 0; i < m.n_el(); ++i) big = std::max(big, std::hypot(dq[3 * i], dq[3 * i + 1]));
      if (big > max_move) dq *= max_move / big;
    }
    // damped step: accept the largest of 1, 1/2, 1/4, ... that lowers the residual
    double step = 1.0;
    bool improved = false;
    for (int ls = 0; ls < 12; ++ls, step *= 0.5) {
      poll_stop(stop, m.n_el());
      Eigen::VectorXd trial = y;
      trial.head(ne) += step * dq;
      const double r = residual(trial);
      if (r < res) {
        y = trial;
        res = r;
        improved = true;
        break;
      }
    }
    if (!improved) break;
  }
  return residual(y);
}

}  // namespace

Scene build_scene(const SceneDef& d, const std::atomic<bool>* stop) {
  validate(d);
  Scene sc;
  Model& m = sc.model;
  const BeltDef& bd = d.belt;
  const int n = bd.elements;
  sc.inputs = scene_inputs(d);

  // pulleys, in definition order
  for (const PulleyDef& p : d.pulleys) {
    Pulley q;
    q.name = p.name;
    q.centre = p.centre;
    q.radius = p.radius;
    q.inertia = p.inertia;
    q.wrap = p.wrap;
    m.pulleys.push_back(q);
    sc.drive.pulleys.push_back(PulleyDrive{p.kinematic, p.torque, p.speed});
  }
  // route order and the pitch-line route
  sc.route_names = bd.route;
  if (sc.route_names.empty())
    for (const PulleyDef& p : d.pulleys) sc.route_names.push_back(p.name);
  std::vector<RouteCircle> circles;
  for (const std::string& nm : sc.route_names) {
    const int j = sc.find_pulley(nm);
    sc.route_pulleys.push_back(j);
    const Pulley& p = m.pulleys[j];
    const int sense = p.wrap == WrapSide::inside ? bd.loop_sense : -bd.loop_sense;
    circles.push_back({p.centre, p.radius, sense});
  }
  sc.route = make_route(circles, bd.loop_sense, sc.route_names);
  const double pitch = sc.route.length / n;

  // enough elements on every wrap to resolve the contact
  for (size_t k = 0; k < circles.size(); ++k) {
    const double on_wrap = sc.route.arcs[k].length() / pitch;
    if (on_wrap < 3.0) {
      std::ostringstream s;
      s << "belt.elements: too few elements for the wrap on pulley '" << sc.route_names[k] << "' ("
        << sc.route.arcs[k].angle * 180 / M_PI << " deg holds " << on_wrap << " elements, at least 3 needed; got "
        << n << " elements)";
      throw ParameterError(s.str());
    }
  }

  // belt properties per SDE (DESIGN §2), from the rest length l0 of an element: its rigid rod,
  // since an SDE's spring is unstretched at zero gap. The rigidities refer to l0: k = EA/l0,
  // k_t = EI/l0, c = axial_damping/l0, c_t = bending_viscosity/l0 (or bending_damping per SDE
  // as the paper gives it); the mass is ρ·l0, ρ per metre of unstretched belt.
  Belt& b = m.belt;
  b.n = n;
  b.pitch = pitch;
  b.e_tra = bd.e_tra;
  b.e_tor = bd.e_tor;
  sc.reading = bd.reading;
  const bool rigid = bd.reading == StiffnessReading::rigidity;
  auto set_rest = [&](double l0) {
    b.rigid_length = l0;
    b.mass = bd.mass_per_length * l0;
    b.rot_inertia = b.mass * l0 * l0 / 12.0;
    if (rigid) {
      b.k = bd.EA / l0;
      b.kt = bd.EI / l0;
      b.c = bd.axial_damping / l0;
      b.ct = bd.bending_viscosity ? *bd.bending_viscosity / l0 : bd.bending_damping;
    } else {
      b.k = bd.k, b.kt = bd.kt, b.c = bd.c, b.ct = bd.ct;
    }
  };
  set_rest(pitch);
  // per-SDE values that overflow (EA = 1e308 over a pitch of centimetres) make every force NaN
  for (const auto& [name, v, given, unit] :
       {std::tuple{"belt.k (EA / l0)", b.k, rigid ? bd.EA : bd.k, "N"},
        std::tuple{"belt.kt (EI / l0)", b.kt, rigid ? bd.EI : bd.kt, "N·m²"},
        std::tuple{"belt.c (axial_damping / l0)", b.c, rigid ? bd.axial_damping : bd.c, "N·s"}})
    if (!std::isfinite(v) || v > 1e15) reject(name, "is beyond what double precision integrates (> 1e15 per SDE)", given, unit);
  // the tension at rest, given or estimated from the rest length (straight spans: T = k·(l - l0)^e);
  // `how` names the way it was given, for the messages
  struct {
    const char* key;
    double value;
    const char* unit;
  } how = {"belt.pretension", bd.pretension, "N"};
  if (bd.tensioning == Tensioning::rest_length) how = {"belt.rest_length", bd.rest_length, "m"};
  if (bd.tensioning == Tensioning::strain) how = {"belt.strain", bd.strain, ""};
  double rest = 0;  // [m] l0 when the rest length is given
  if (bd.tensioning == Tensioning::rest_length) rest = bd.rest_length / n;
  if (bd.tensioning == Tensioning::strain) rest = pitch / (1 + bd.strain);
  if (rest > 0) {
    if (!(rest < pitch)) {
      std::ostringstream s;
      s << "is not shorter than the route's pitch line (" << sc.route.length
        << " m): the belt would hang slack; it must be stretched to be mounted";
      reject(how.key, s.str(), how.value, how.unit);
    }
    set_rest(rest);
  }
  const double tension0 = rest > 0 ? b.k * std::pow(pitch - rest, b.e_tra) : bd.pretension;
  if (std::pow(tension0 / b.k, 1.0 / b.e_tra) >= 0.5 * pitch)
    reject(how.key, "stretches each SDE by more than half a pitch: lower it or stiffen the belt", how.value,
           how.unit);
  // The static start holds straight spans at the tension at rest: a belt whose weight over its
  // longest span passes that tension (ρ·|g|·L > T: a sag above L/8, δ = ρgL²/8T) hangs instead
  // (on the paper's drive from gravity = 1.8e4 m/s²; at 1e4 the spans already carry 554 N, not 500)
  {
    double longest = 0;
    for (const Route::Span& sp : sc.route.spans) longest = std::max(longest, sp.length);
    const double weight = bd.mass_per_length * std::abs(d.gravity) * longest;
    if (!(weight <= tension0)) {
      std::ostringstream s;
      s.precision(6);
      s << "makes the belt's weight over its longest span (ρ·g·L = " << weight << " N over " << longest
        << " m) larger than its tension at rest (" << tension0 << " N): the belt would hang rather than span its "
        << "pulleys; lower gravity or belt.mass_per_length, or tension the belt more";
      reject("gravity", s.str(), d.gravity, "m/s²");
    }
  }
  m.contact = d.contact;
  if (d.contact_per_length.c1) m.contact.c1 = *d.contact_per_length.c1 * pitch;
  if (d.contact_per_length.c2) m.contact.c2 = *d.contact_per_length.c2 * pitch;
  if (d.contact_per_length.b) m.contact.b = *d.contact_per_length.b * pitch;
  m.friction = d.friction;
  m.gravity = d.gravity;
  m.track_energy = d.track_energy;

  // static penetration on each pulley and the offset path of the element centres
  std::vector<RouteCircle> inner = circles;
  sc.penetration.assign(m.n_p(), 0.0);
  for (size_t k = 0; k < circles.size(); ++k) {
    double p0 = 0;
    for (int it = 0; it < 8; ++it) {
      const double alpha = 2 * std::asin(std::min(1.0, pitch / (2 * (circles[k].radius - p0))));
      p0 = static_penetration(m.contact, 2 * tension0 * std::sin(alpha / 2));
    }
    if (!std::isfinite(p0)) {
      std::ostringstream c;
      c.precision(6);
      c << "gives no finite static penetration on '" << sc.route_names[k] << "' with contact.c2 = " << d.contact.c2
        << " N/m (beyond double precision)";
      reject("contact.c1", c.str(), d.contact.c1, "N/m²");
    }
    if (p0 >= 0.5 * circles[k].radius)
      reject("contact stiffness", "lets the belt sink more than half the radius of '" + sc.route_names[k] + "'", p0,
             "m");
    sc.penetration[sc.route_pulleys[k]] = p0;
    inner[k].radius = circles[k].radius - p0;
  }
  const Route path = make_route(inner, bd.loop_sense, sc.route_names);

  // n elements that close the loop: with the pretension given, the rigid length l0 whose SDE
  // gaps carry it (bisection on the closure, the gap following l0 through k = EA/l0); with the
  // rest length given, the gap (bisection on the closure)
  double gap = 0;
  if (rest > 0) {
    double lo = 0, hi = 0.5 * pitch;
    if (walk(path, n, 0.5 * rest, 0, nullptr) >= path.length)
      reject(how.key, "leaves the belt slack on the pulleys (its contact shortens the path): stretch it more",
             how.value, how.unit);
    for (int it = 0; it < 100; ++it) {
      poll_stop(stop, n);
      const double g = 0.5 * (lo + hi);
      (walk(path, n, 0.5 * rest, g, nullptr) < path.length ? lo : hi) = g;
    }
    gap = 0.5 * (lo + hi);
  } else {
    // the gap that carries the pretension with k = EA/l0 (per-SDE: k as given)
    auto gap_for = [&](double l0) {
      return std::pow(bd.pretension / (rigid ? bd.EA / l0 : bd.k), 1.0 / b.e_tra);
    };
    double lo = 0.2 * pitch, hi = pitch;
    for (int it = 0; it < 100; ++it) {
      poll_stop(stop, n);  // each walk is O(n): 25 ms at 5000 elements
      const double le = 0.5 * (lo + hi);
      (walk(path, n, 0.5 * le, gap_for(le), nullptr) < path.length ? lo : hi) = le;
    }
    set_rest(0.5 * (lo + hi));
    gap = gap_for(b.rigid_length);
  }
  std::vector<double> s;
  walk(path, n, 0.5 * b.rigid_length, gap, &s);

  // the state: elements at rest on the path, pulleys at rest (kinematic ones at their speed)
  sc.y0.setZero(m.n_state());
  double phi_prev = 0;
  for (int i = 0; i < n; ++i) {
    Vec2 C, T;
    path.eval(s[i], C, T);
    double phi = std::atan2(T.y(), T.x());
    if (i > 0) phi = phi_prev + wrap_angle(phi - phi_prev);
    sc.y0[3 * i] = C.x();
    sc.y0[3 * i + 1] = C.y();
    sc.y0[3 * i + 2] = phi;
    phi_prev = phi;
  }
  // friction coefficient of each element, possibly from where it starts
  std::vector<double>& mu = sc.drive.mu;
  mu = bd.mu_per_element.empty() ? std::vector<double>(n, bd.mu) : bd.mu_per_element;
  {
    ElementSite site;
    site.length = path.length;
    double acc = 0;
    for (size_t k = 0; k < path.spans.size(); ++k) {
      site.leaves[sc.route_names[k]] = acc;
      acc += path.spans[k].length;
      const size_t next = (k + 1) % path.spans.size();
      site.meets[sc.route_names[next]] = acc;
      acc += path.arcs[next].length();
    }
    sc.sites.reserve(n);
    for (int i = 0; i < n; ++i) {
      site.index = i;
      site.centre = Vec2(sc.y0[3 * i], sc.y0[3 * i + 1]);
      site.s = s[i];
      site.pulley.clear();
      for (size_t k = 0; k < path.spans.size(); ++k) {
        const double a = site.meets[sc.route_names[k]], e = site.leaves[sc.route_names[k]];
        const bool on = a <= e ? (s[i] >= a && s[i] <= e) : (s[i] >= a || s[i] <= e);
        if (on) site.pulley = sc.route_names[k];
      }
      sc.sites.push_back(site);
    }
  }
  if (bd.mu_at) {
    for (int i = 0; i < n; ++i) {
      const double mu_i = bd.mu_at(sc.sites[i]);
      require_non_negative("belt.mu of element " + std::to_string(i), mu_i, "");
      mu[i] = mu_i;
    }
  }
  for (int j = 0; j < m.n_p(); ++j)
    if (sc.drive.kinematic(j))  // a run starts after a step at 0
      sc.y0[m.n_coord() + m.pulley_coord(j)] = sc.drive.pulleys[j].speed.eval(0.0, 0.0, true);

  // the static state is found with every pulley at rest (a kinematic pulley's prescribed speed
  // would drag the belt round while it is sought)
  Model at_rest = m;
  Drive rest_drive = sc.drive;
  for (PulleyDrive& p : rest_drive.pulleys)
    if (p.kinematic) p.speed = TimeSpeedLaw{};
  // static solve; then correct the rigid length until the spans carry the pretension (the
  // belt's bending stiffness lifts it off small pulleys, which changes the tension a little).
  // The belt is not changed after the last solve, so the state returned is static for the belt
  // returned (or the residual says it is not, and the trust-region attempt follows).
  constexpr double kConverged = 1.0;  // [m/s²] against accelerations of 1e5..1e9 in the raw placement
  const Eigen::VectorXd placed = sc.y0;
  const Belt placed_belt = b;
  auto attempt = [&](double max_move) {
    sc.y0 = placed;
    b = placed_belt;
    constexpr int kPasses = 12;
    for (int it = 0; it < kPasses; ++it) {
      at_rest.belt = b;
      sc.static_residual = static_solve(at_rest, rest_drive, sc.y0, max_move, stop);
      sc.span_sde.clear();
      double tension = 0;
      for (const Route::Span& sp : sc.route.spans) {
        const int i = sde_nearest(m, sc.y0.data(), 0.5 * (sp.from + sp.to));
        sc.span_sde.push_back(i);
        tension += sde_axial_force(m, sc.y0.data(), sc.y0.data() + m.n_coord(), i);
      }
      sc.static_tension = tension / static_cast<double>(sc.route.spans.size());
      // the rest length given: the tension is what it gives, once converged
      if (rest > 0) {
        if (sc.static_residual < kConverged) break;
        continue;
      }
      if ((std::abs(sc.static_tension - bd.pretension) < 1e-5 * bd.pretension && sc.static_residual < kConverged) ||
          it == kPasses - 1)
        break;
      // dT/dl_e = -k·e·gap^(e-1) along the SDE (k's own change with l_e is a fraction T/EA of it)
      const double g = std::pow(sc.static_tension / b.k, 1.0 / b.e_tra);
      set_rest(b.rigid_length + (sc.static_tension - bd.pretension) / (b.k * b.e_tra * std::pow(g, b.e_tra - 1.0)));
    }
    // every pulley of the route still touched?
    for (size_t k = 0; k < sc.route_pulleys.size(); ++k) {
      const Pulley& p = m.pulleys[sc.route_pulleys[k]];
      int touching = 0;
      for (int i = 0; i < n; ++i) touching += (Vec2(sc.y0[3 * i], sc.y0[3 * i + 1]) - p.centre).norm() < p.radius;
      if (touching == 0) return p.name;
    }
    return std::string();
  };
  // The plain Newton iteration can go astray: with the belt at rest friction holds nothing, so
  // sliding the belt along its path costs no force and K is nearly singular that way. For 80,
  // 120 and 140 elements on the paper's drive the iteration carried the belt along that mode
  // off a pulley, or stopped unconverged. Then it is repeated with a trust region of a tenth of
  // a pitch per step (not always: it lands elsewhere along the free mode, and the plain
  // iteration is what the 60-element results were measured from).
  std::string lost = attempt(0);
  if (!lost.empty() || !(sc.static_residual < kConverged)) {
    lost = attempt(0.1 * b.pitch);
    sc.static_retried = true;
    notify_warning(WarningKind::static_retry, 0.0);
  }
  // the initial state must be finite: parameters far beyond a belt's (each finite, and each
  // within its own rule) can still overflow the static solve
  {
    std::string bad;
    for (Eigen::Index k = 0; k < sc.y0.size() && bad.empty(); ++k)
      if (!std::isfinite(sc.y0[k]))
        bad = (k < 3 * n ? "element " + std::to_string(k / 3) + "'s " + (k % 3 == 2 ? "angle" : "position")
                         : "a pulley's state") + " is " + (std::isnan(sc.y0[k]) ? "NaN" : "infinite");
    for (const auto& [name, v] : {std::pair{"the rigid length", b.rigid_length}, {"the static tension", sc.static_tension},
                                  {"the static residual", sc.static_residual}})
      if (bad.empty() && !std::isfinite(v)) bad = std::string(name) + " is " + (std::isnan(v) ? "NaN" : "infinite");
    if (!bad.empty()) {
      std::ostringstream msg;
      msg.precision(6);
      msg << "scene: the belt's static initial state is not finite (" << bad << "): the parameters are beyond what "
          << "double precision resolves (the values that scale it: gravity = " << d.gravity << " m/s², the tension at rest = "
          << tension0 << " N, per-SDE k = " << b.k << " N/m, contact.c1 = " << d.contact.c1
          << " N/m², belt.mass_per_length = " << bd.mass_per_length << " kg/m)";
      throw ParameterError(msg.str());
    }
  }
  if (!lost.empty()) {
    std::ostringstream msg;
    msg << "belt.elements: could not find the belt's static initial state with " << n
        << " elements (the iteration left pulley '" << lost << "' untouched); a few elements more or "
        << "fewer usually works";
    throw ParameterError(msg.str());
  }
  return sc;
}

}  // namespace beltsim
