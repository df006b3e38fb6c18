// The stages of build_scene (scene/build.hpp): the belt's route and its initial static state
// (docs/model.md, Initial state).
//
// Initial state. The elements' centres are placed on the route offset inwards by the static
// penetration p0_j on each pulley (c1·p0² + c2·p0 = N0 = 2·T0·sin(α/2), α the angle one pitch
// subtends), each rod along the path's tangent at its centre. Walking along the path, each
// centre is put where the gap of its SDE to the previous element is the one that carries the
// pretension, |d| = (T0/k)^(1/e_tra); the rigid length l_e is chosen (bisection) so that n
// elements close the loop exactly. This is an equilibrium on the spans and on the arcs, but not
// quite where a span meets an arc; a few Newton iterations on the elements' static equations
// (pulleys held, belt at rest, gravity on) remove the rest (f(q) = 0 with K = ∂f/∂q).
#include "scene/build.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/SparseLU>

#include "integrate/warnings.hpp"
#include "io/number_text.hpp"
#include "model/forces.hpp"
#include "model/rhs.hpp"
#include "model/sparse.hpp"
#include "scene/parameters.hpp"
#include "scene/validate.hpp"

namespace beltsim {

namespace build {

namespace {

// the build's poll (BuildWatch): stopped, or its progress told in `stage`
void poll(BuildWatch& w, const char* stage) {
  if (w.stop && w.stop->load(std::memory_order_relaxed))
    throw BuildInterrupted(
        "scene: the build was interrupted while placing the belt and solving its static initial state (" +
        std::to_string(w.elements) + " elements); no scene was made");
  w.stage = stage;
  if (w.progress) w.progress(w);
}

constexpr const char* kPlacing = "placing the belt";
constexpr const char* kStatic = "static state";

}  // namespace

std::vector<Pulley> make_pulleys(const SceneDef& d) {
  std::vector<Pulley> out;
  for (const PulleyDef& p : d.pulleys) {
    Pulley q;
    q.name = p.name;
    q.centre = p.centre;
    q.radius = p.radius;
    q.inertia = p.inertia;
    q.wrap = p.wrap;
    out.push_back(q);
  }
  return out;
}

Drive make_drive(const SceneDef& d) {
  Drive out;
  for (const PulleyDef& p : d.pulleys) out.pulleys.push_back(PulleyDrive{p.kinematic, p.torque, p.speed});
  return out;
}

RouteOrder route_order(const SceneDef& d, const std::vector<Pulley>& pulleys) {
  const BeltDef& bd = d.belt;
  RouteOrder r;
  r.names = bd.route;
  if (r.names.empty())
    for (const PulleyDef& p : d.pulleys) r.names.push_back(p.name);
  for (const std::string& nm : r.names) {
    int j = 0;
    while (pulleys[j].name != nm) ++j;  // validate: every name of the route is a pulley's
    r.pulleys.push_back(j);
    const Pulley& p = pulleys[j];
    const int sense = p.wrap == WrapSide::inside ? bd.loop_sense : -bd.loop_sense;
    r.circles.push_back({p.centre, p.radius, sense});
  }
  return r;
}

void set_rest_length(Belt& b, const BeltDef& bd, double l0) {
  b.rigid_length = l0;
  b.mass = bd.mass_per_length * l0;
  b.rot_inertia = b.mass * l0 * l0 / 12.0;
  if (bd.reading == StiffnessReading::rigidity) {
    b.k = bd.EA / l0;
    b.kt = bd.EI / l0;
    b.c = bd.axial_damping / l0;
    b.ct = bd.bending_viscosity ? *bd.bending_viscosity / l0 : bd.bending_damping;
  } else {
    b.k = bd.k, b.kt = bd.kt, b.c = bd.c, b.ct = bd.ct;
  }
}

TensionAtRest tension_at_rest(const BeltDef& bd, double route_length, Belt& b) {
  TensionAtRest t{"belt.pretension", bd.pretension};
  if (bd.tensioning == Tensioning::rest_length) t.key = "belt.rest_length", t.value = bd.rest_length;
  if (bd.tensioning == Tensioning::strain) t.key = "belt.strain", t.value = bd.strain;
  if (bd.tensioning == Tensioning::rest_length) t.rest = bd.rest_length / b.n;
  if (bd.tensioning == Tensioning::strain) t.rest = b.pitch / (1 + bd.strain);
  if (t.rest > 0) {
    if (!(t.rest < b.pitch)) {
      std::ostringstream s;
      // (a rest length: a strain <= 0 is refused by its rule)
      s << "is not shorter than the route's pitch line (" << route_length
        << " m): the belt would hang slack; it must be stretched to be mounted: lower it below the route's length (a "
           "PK belt is mounted at a few tenths of a per cent: "
        << rounded_text(route_length / 1.005, 6) << " m is 0.5 %)";
      reject(t.key, s.str(), t.value);
    }
    set_rest_length(b, bd, t.rest);
  }
  t.tension = t.rest > 0 ? b.k * std::pow(b.pitch - t.rest, b.e_tra) : bd.pretension;
  // the strain at rest against a belt's (scene/validate.hpp); for a pretension T/EA (the rest
  // length is still the pitch here: k = EA/pitch), which its build then gives within the contact's share
  const double gap = std::pow(t.tension / b.k, 1.0 / b.e_tra);
  const StrainAtRest s{t.key,
                       t.value,
                       std::string(find_parameter(t.key)->unit),
                       t.rest > 0 ? b.pitch / t.rest - 1 : gap / b.rigid_length,
                       t.tension,
                       b.k * b.rigid_length,
                       route_length};
  check_strain_at_rest(s, gap >= 0.5 * b.pitch);
  return t;
}

Contact element_contact(const SceneDef& d, double pitch) {
  Contact c = d.contact;
  if (d.contact_per_length.c1) c.c1 = *d.contact_per_length.c1 * pitch;
  if (d.contact_per_length.c2) c.c2 = *d.contact_per_length.c2 * pitch;
  if (d.contact_per_length.b) c.b = *d.contact_per_length.b * pitch;
  return c;
}

double static_penetration(const Contact& c, double pitch, double radius, double tension) {
  double p0 = 0;
  for (int it = 0; it < 8; ++it) {
    const double alpha = 2 * std::asin(std::min(1.0, pitch / (2 * (radius - p0))));
    const double N0 = 2 * tension * std::sin(alpha / 2);
    p0 = c.c1 > 0 ? (-c.c2 + std::sqrt(c.c2 * c.c2 + 4 * c.c1 * N0)) / (2 * c.c1) : N0 / c.c2;
  }
  return p0;
}

std::vector<double> penetrations(const RouteOrder& order, const Contact& c, double pitch, double tension,
                                 const SceneDef& d) {
  std::vector<double> out;
  for (size_t k = 0; k < order.circles.size(); ++k) {
    const double p0 = static_penetration(c, pitch, order.circles[k].radius, tension);
    if (!std::isfinite(p0)) {
      reject("contact.c1",
             "gives no finite static penetration on '" + order.names[k] +
                 "' with contact.c2 = " + rounded_text(d.contact.c2, 6) + " N/m (beyond double precision)",
             d.contact.c1);
    }
    if (p0 >= 0.5 * order.circles[k].radius)
      reject("contact stiffness", "lets the belt sink more than half the radius of '" + order.names[k] + "'", p0, "m");
    out.push_back(p0);
  }
  return out;
}

Route centre_path(const RouteOrder& order, const std::vector<double>& penetration, int loop_sense) {
  std::vector<RouteCircle> inner = order.circles;
  for (size_t k = 0; k < inner.size(); ++k) inner[k].radius = order.circles[k].radius - penetration[k];
  return make_route(inner, loop_sense, order.names);
}

// Whether a bisection step on [lo, hi] at its midpoint mid is its last that can change anything:
// mid has rounded to an end (or the ends met), so after this step's assignment every later step
// takes the same midpoint and leaves [lo, hi] as it is. The bisections below run a fixed count of
// steps, which on short intervals goes past the doubles' resolution; they stop here instead, with
// the same result.
static bool at_resolution(double mid, double lo, double hi) {
  return mid == lo || mid == hi || lo == hi;
}

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
      const bool last = at_resolution(mid, lo, hi);
      (sigma < gap ? lo : hi) = mid;
      if (last) break;
    }
    s_prev = 0.5 * (lo + hi);
    if (s_out && i < n) s_out->push_back(s_prev);
  }
  return s_prev;
}

double close_loop(const Route& path, int n, const BeltDef& bd, const TensionAtRest& t, Belt& b, BuildWatch& watch) {
  if (t.rest > 0) {
    double lo = 0, hi = 0.5 * b.pitch;
    if (walk(path, n, 0.5 * t.rest, 0, nullptr) >= path.length)
      reject(t.key, "leaves the belt slack on the pulleys (its contact shortens the path): stretch it more", t.value);
    for (int it = 0; it < 100; ++it) {
      poll(watch, kPlacing);
      const double g = 0.5 * (lo + hi);
      const bool last = at_resolution(g, lo, hi);
      (walk(path, n, 0.5 * t.rest, g, nullptr) < path.length ? lo : hi) = g;
      if (last) break;
    }
    return 0.5 * (lo + hi);
  }
  // the gap that carries the pretension with k = EA/l0 (per-SDE: k as given)
  const bool rigid = bd.reading == StiffnessReading::rigidity;
  auto gap_for = [&](double l0) { return std::pow(bd.pretension / (rigid ? bd.EA / l0 : bd.k), 1.0 / b.e_tra); };
  double lo = 0.2 * b.pitch, hi = b.pitch;
  for (int it = 0; it < 100; ++it) {
    poll(watch, kPlacing);  // each walk is O(n): 25 ms at 5000 elements
    const double le = 0.5 * (lo + hi);
    const bool last = at_resolution(le, lo, hi);
    (walk(path, n, 0.5 * le, gap_for(le), nullptr) < path.length ? lo : hi) = le;
    if (last) break;
  }
  set_rest_length(b, bd, 0.5 * (lo + hi));
  return gap_for(b.rigid_length);
}

Eigen::VectorXd place(const Model& m, const Route& path, const std::vector<double>& s) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(m.n_state());
  double phi_prev = 0;
  for (int i = 0; i < m.n_el(); ++i) {
    Vec2 C, T;
    path.eval(s[i], C, T);
    double phi = std::atan2(T.y(), T.x());
    if (i > 0) phi = phi_prev + wrap_angle(phi - phi_prev);
    y[3 * i] = C.x();
    y[3 * i + 1] = C.y();
    y[3 * i + 2] = phi;
    phi_prev = phi;
  }
  return y;
}

void set_start_speeds(const Model& m, const Drive& dr, Eigen::VectorXd& y) {
  for (int j = 0; j < m.n_p(); ++j)  // a run starts after a step at 0
    if (dr.kinematic(j)) y[m.n_coord() + m.pulley_coord(j)] = dr.pulleys[j].speed.eval(0.0, 0.0, true);
}

std::vector<ElementSite> element_sites(const Route& path, const std::vector<std::string>& names,
                                       const Eigen::VectorXd& y0, const std::vector<double>& s) {
  const int n = static_cast<int>(s.size());
  ElementSite site;
  site.length = path.length;
  double acc = 0;
  for (size_t k = 0; k < path.spans.size(); ++k) {
    site.leaves[names[k]] = acc;
    acc += path.spans[k].length;
    const size_t next = (k + 1) % path.spans.size();
    site.meets[names[next]] = acc;
    acc += path.arcs[next].length();
  }
  std::vector<ElementSite> sites;
  sites.reserve(n);
  for (int i = 0; i < n; ++i) {
    site.index = i;
    site.centre = Vec2(y0[3 * i], y0[3 * i + 1]);
    site.s = s[i];
    site.pulley.clear();
    for (size_t k = 0; k < path.spans.size(); ++k) {
      const double a = site.meets[names[k]], e = site.leaves[names[k]];
      const bool on = a <= e ? (s[i] >= a && s[i] <= e) : (s[i] >= a || s[i] <= e);
      if (on) site.pulley = names[k];
    }
    sites.push_back(site);
  }
  return sites;
}

void set_segment_laws(Model& m, const SceneDef& d, const std::vector<double>& s) {
  m.laws.clear();
  m.law_of.clear();
  if (d.friction_segments.empty()) return;
  m.law_of.assign(s.size(), 0);
  for (size_t k = 0; k < d.friction_segments.size(); ++k) {
    const FrictionSegment& g = d.friction_segments[k];
    m.laws.push_back(g.law);
    for (size_t i = 0; i < s.size(); ++i) {
      const bool in = g.from <= g.to ? (s[i] >= g.from && s[i] <= g.to) : (s[i] >= g.from || s[i] <= g.to);
      if (in) m.law_of[i] = static_cast<unsigned char>(k + 1);
    }
  }
}

std::vector<double> element_mu(const BeltDef& bd, const std::vector<ElementSite>& sites) {
  const int n = bd.elements;
  std::vector<double> mu = bd.mu_per_element.empty() ? std::vector<double>(n, bd.mu) : bd.mu_per_element;
  if (bd.mu_at) {
    for (int i = 0; i < n; ++i) {
      const double v = bd.mu_at(sites[i]);
      require_mu("belt.mu of element " + std::to_string(i), v);
      mu[i] = v;
    }
  }
  return mu;
}

double static_solve(const Model& m, const Drive& dr, Eigen::VectorXd& y, double max_move, BuildWatch& watch) {
  const int ne = 3 * m.n_el();
  Eigen::VectorXd f(m.n_coord());
  Jacobian J;
  J.resize(m);
  Eigen::SparseMatrix<double> A;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  auto residual = [&](const Eigen::VectorXd& yy) {
    forces(m, dr, 0.0, yy.data(), f.data());
    double r = 0;
    for (int k = 0; k < ne; ++k) r = std::max(r, std::abs(f[k] / m.mass_of(k)));
    return r;
  };
  double res = residual(y);
  for (int it = 0; it < 30 && res > 1e-9; ++it) {
    ++watch.newton;
    poll(watch, kStatic);
    jacobian(m, dr, 0.0, y.data(), J);
    assemble(m, dr, 0.0, 0.0, J.C, J.K, ne, A);  // A = -K_ee, the same pattern at every call
    poll(watch, kStatic);
    if (it == 0) lu.analyzePattern(A);
    lu.factorize(A);
    poll(watch, kStatic);
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
      poll(watch, kStatic);
      Eigen::VectorXd trial = y;
      trial.head(ne) += step * dq;
      const double r = residual(trial);
      if (r < res) {
        y = trial;
        res = r;
        watch.residual = r;
        improved = true;
        break;
      }
    }
    if (!improved) break;
  }
  return residual(y);
}

double span_tension(const Model& m, const Route& route, const Eigen::VectorXd& y) {
  double tension = 0;
  for (const Route::Span& sp : route.spans) tension += span_force(m, sp, y.data());
  return tension / static_cast<double>(route.spans.size());
}

std::string settle(Scene& sc, const BeltDef& bd, bool rest_given, BuildWatch& watch) {
  const Model& m = sc.model;
  Belt& b = sc.model.belt;
  // the static state is found with every pulley at rest (a kinematic pulley's prescribed speed
  // would drag the belt round while it is sought)
  Model at_rest = m;
  Drive held = sc.drive;
  for (PulleyDrive& p : held.pulleys)
    if (p.kinematic) p.speed = TimeSpeedLaw{};
  // static solve; then correct the rigid length until the spans carry the pretension (the
  // belt's bending stiffness lifts it off small pulleys, which changes the tension a little).
  // The belt is not changed after the last solve, so the state returned is static for the belt
  // returned (or the residual says it is not, and the trust-region attempt follows).
  constexpr double kConverged = kStaticConverged;
  const Eigen::VectorXd placed = sc.y0;
  const Belt placed_belt = b;
  auto attempt = [&](double max_move) {
    sc.y0 = placed;
    b = placed_belt;
    constexpr int kPasses = 12;
    double last_length = 0, last_tension = 0;  // the pass before's, for the secant
    for (int it = 0; it < kPasses; ++it) {
      at_rest.belt = b;
      sc.static_residual = static_solve(at_rest, held, sc.y0, max_move, watch);
      sc.static_tension = span_tension(m, sc.route, sc.y0);
      // the rest length given: the tension is what it gives, once converged
      if (rest_given) {
        if (sc.static_residual < kConverged) break;
        continue;
      }
      if ((std::abs(sc.static_tension - bd.pretension) < 1e-5 * bd.pretension && sc.static_residual < kConverged) ||
          it == kPasses - 1)
        break;
      // dT/dl_e: the SDE's alone, -k·e·gap^(e-1) (k's own change with l_e is a fraction T/EA of
      // it), while it at least halves the miss a pass; else the secant through the last two passes,
      // which also has the contact's give (on a belt much stiffer than its contact the SDE's slope
      // alone moved the tension a few per cent a pass: 516 N for 500 after 12 passes at EA 3e6 N,
      // and the static solve stalled from 6e6 N on)
      const double g = std::pow(sc.static_tension / b.k, 1.0 / b.e_tra);
      double slope = -b.k * b.e_tra * std::pow(g, b.e_tra - 1.0);
      const double miss = sc.static_tension - bd.pretension, last_miss = last_tension - bd.pretension;
      if (it > 0 && b.rigid_length != last_length && std::abs(miss) > 0.5 * std::abs(last_miss)) {
        const double secant = (sc.static_tension - last_tension) / (b.rigid_length - last_length);
        if (std::isfinite(secant) && secant < 0) slope = secant;
      }
      last_length = b.rigid_length, last_tension = sc.static_tension;
      set_rest_length(b, bd, b.rigid_length - miss / slope);
    }
    // every pulley of the route still touched?
    for (const int j : sc.route_pulleys) {
      const Pulley& p = m.pulleys[j];
      int touching = 0;
      for (int i = 0; i < m.n_el(); ++i) touching += (Vec2(sc.y0[3 * i], sc.y0[3 * i + 1]) - p.centre).norm() < p.radius;
      if (touching == 0) return p.name;
    }
    return std::string();
  };
  // The plain Newton iteration can go astray: with the belt at rest friction holds nothing, so
  // sliding the belt along its path costs no force and K is nearly singular that way, and the
  // iteration may carry the belt along that mode off a pulley or stop unconverged (on the
  // paper's drive at some element counts, 80, 120 and 140 among them). Then it is repeated with
  // a trust region of a tenth of a pitch per step. The plain iteration goes first because the
  // trust region lands elsewhere along the free mode, and the docs' 60-element results are the
  // plain iteration's.
  std::string lost = attempt(0);
  if (!lost.empty() || !(sc.static_residual < kConverged)) {
    lost = attempt(0.1 * b.pitch);
    sc.static_retried = true;
    notify_warning(WarningKind::static_retry, 0.0);
  }
  return lost;
}

}  // namespace build

}  // namespace beltsim
