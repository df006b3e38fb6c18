#include "scene/scene_io.hpp"

#include <climits>
#include <cmath>
#include <set>

#include "scene/build.hpp"
#include "scene/law_io.hpp"
#include "scene/validate.hpp"

namespace beltsim {

namespace {

// ParameterError (the validation's reason and value) as a CheckpointError naming the line just read
template <class F>
void checked(CheckpointReader& r, F&& f) {
  std::string error;
  try {
    f();
  } catch (const ParameterError& e) {
    error = e.what();
  }
  if (!error.empty()) r.fail(error);
}

// ---- the route and the element sites -------------------------------------------------------

void write_route(CheckpointWriter& w, const Route& route) {
  w.line("route.spans", static_cast<long>(route.spans.size()));
  for (const Route::Span& s : route.spans) {
    w.fixed("span.from", {s.from.x(), s.from.y()});
    w.fixed("span.to", {s.to.x(), s.to.y()});
    w.line("span.length", s.length);
  }
  w.line("route.arcs", static_cast<long>(route.arcs.size()));
  for (const Route::Arc& a : route.arcs) {
    w.fixed("arc.centre", {a.centre.x(), a.centre.y()});
    w.line("arc.radius", a.radius);
    w.line("arc.sense", a.sense);
    w.line("arc.start_angle", a.start_angle);
    w.line("arc.angle", a.angle);
  }
  w.line("route.length", route.length);
}

Vec2 read_vec2(CheckpointReader& r, const std::string& k) {
  const std::vector<double> v = r.line_fixed(k, 2);
  return {v[0], v[1]};
}

// a route round np pulleys: np spans and np arcs
Route read_route(CheckpointReader& r, size_t np) {
  Route route;
  auto exactly = [&](const std::string& key, size_t lines_each) {
    r.open(key);
    const size_t n = r.group_count(lines_each, np);
    if (n != np) r.fail(std::to_string(n) + " for " + std::to_string(np) + " pulleys");
    r.close();
    return n;
  };
  for (size_t k = 0, n = exactly("route.spans", 3); k < n; ++k) {
    Route::Span& s = route.spans.emplace_back();
    s.from = read_vec2(r, "span.from");
    s.to = read_vec2(r, "span.to");
    s.length = r.line_num("span.length");
  }
  for (size_t k = 0, n = exactly("route.arcs", 5); k < n; ++k) {
    Route::Arc& a = route.arcs.emplace_back();
    a.centre = read_vec2(r, "arc.centre");
    a.radius = r.line_num("arc.radius");
    a.sense = static_cast<int>(r.line_int("arc.sense", -1, 1));
    a.start_angle = r.line_num("arc.start_angle");
    a.angle = r.line_num("arc.angle");
  }
  route.length = r.line_num("route.length");
  return route;
}

// the parameter of an input's name: "belt.EA" is itself, "pulley.driver.radius" is pulley.radius
// for a pulley of the model; nullptr when none
const Parameter* input_parameter(const std::string& name, const Model& m) {
  for (const Pulley& p : m.pulleys) {
    const std::string pre = "pulley." + p.name + ".";
    if (name.compare(0, pre.size(), pre) == 0) return find_parameter("pulley." + name.substr(pre.size()));
  }
  // a spray zone's: "spray.2.radius" is spray.radius
  const size_t dot = name.find('.', 6);
  if (name.compare(0, 6, "spray.") == 0 && dot != std::string::npos && dot > 6 &&
      name.find_first_not_of("0123456789", 6) == dot)
    return find_parameter("spray." + name.substr(dot + 1));
  // a friction segment's: "friction.segments.2.from" is friction.segments.from, ".law" and the
  // law's keys are the friction table's
  const std::string_view seg = "friction.segments.";
  const size_t end = name.find('.', seg.size());
  if (name.compare(0, seg.size(), seg) == 0 && end != std::string::npos && end > seg.size() &&
      name.find_first_not_of("0123456789", seg.size()) == end) {
    const std::string key = name.substr(end + 1);
    if (key == "from" || key == "to") return find_parameter("friction.segments." + key);
    return key == "dv" || key == "segments" ? nullptr : find_parameter("friction." + key);
  }
  return find_parameter(name);
}

}  // namespace

// the scene's definition as its model and route give it back: what validate(SceneDef) checks
// of a script's scene, it checks of a checkpoint's. The belt is given per SDE (as built) and by
// its rest length; the element count needs no allow_large (every element's values are in the
// file, so the file's size bounds it).
SceneDef definition(const Scene& sc) {
  const Model& m = sc.model;
  SceneDef d;
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& p = m.pulleys[j];
    const PulleyDrive& pd = sc.drive.pulleys[j];
    d.pulleys.push_back({p.name, p.centre, p.radius, p.inertia, p.wrap, pd.kinematic, pd.torque, pd.speed, {}, {}});
    if (p.coupling >= 0) {
      const Coupling& c = m.couplings[p.coupling];
      CouplingDef& cd = d.pulleys.back().coupling.emplace();
      cd.inertia = c.inertia, cd.stiffness = c.stiffness, cd.damping = c.damping, cd.one_way = c.one_way;
      if (c.one_way) cd.hub_inertia = c.hub_inertia, cd.lock_damping = c.lock_damping, cd.drag_torque = c.drag_torque;
    }
    if (p.arm < 0) continue;
    const Arm& a = m.arms[p.arm];
    TensionerDef& t = d.pulleys.back().tensioner.emplace();
    t.pivot = a.pivot, t.inertia = a.inertia, t.stiffness = a.stiffness, t.damping = a.damping;
    t.friction_torque = a.friction_torque, t.friction_speed = a.friction_speed, t.asymmetric = a.asymmetric;
  }
  BeltDef& b = d.belt;
  b.elements = m.belt.n;
  b.tensioning = Tensioning::rest_length;
  b.rest_length = m.belt.rigid_length * m.belt.n;
  b.route = sc.route_names;
  b.reading = StiffnessReading::per_sde;
  b.k = m.belt.k, b.c = m.belt.c, b.kt = m.belt.kt, b.ct = m.belt.ct;
  b.e_tra = m.belt.e_tra, b.e_tor = m.belt.e_tor;
  b.mass_per_length = m.belt.mass / m.belt.rigid_length;  // the build's m = ρ·l0 (build::set_rest_length)
  b.mu_per_element = sc.drive.mu;
  d.contact = m.contact;
  d.friction = m.friction;
  d.gravity = m.gravity;
  d.track_energy = m.track_energy;
  d.allow_large = true;
  d.spray = sc.drive.spray.zones;
  return d;
}

// ---- the drive -----------------------------------------------------------------------------

void write_drive(CheckpointWriter& w, const Model& m, const Drive& d) {
  w.line("restart_time", d.restart_time);
  for (int j = 0; j < m.n_p(); ++j) {
    const PulleyDrive& p = d.pulleys[j];
    w.line("pulley.drive", m.pulleys[j].name);
    w.word("pulley.drive.by", p.kinematic ? "speed" : "torque");
    write_law(w, p.torque, "pulley.torque");
    write_law(w, p.speed, "pulley.speed");
  }
  w.line("belt.mu", d.mu);
  if (d.spray.any()) {  // only a drive with spray zones has this part
    const Spray& sp = d.spray;
    w.line("spray", static_cast<long>(sp.zones.size()));
    for (const SprayZone& z : sp.zones) {
      w.fixed("spray.centre", {z.centre.x(), z.centre.y()});
      w.fixed("spray.zone", {z.radius, z.mu, z.from, z.to, z.drying_length});
      w.line("spray.enabled", z.enabled);
      w.line("spray.on", z.on);
    }
    std::vector<int> zone, drying;
    std::vector<double> t_in, mu_wet, t_wet, rate;
    for (const ElementSpray& e : sp.el) {
      zone.push_back(e.zone), drying.push_back(e.drying ? 1 : 0), t_in.push_back(e.t_in);
      mu_wet.push_back(e.mu_wet), t_wet.push_back(e.t_wet), rate.push_back(e.rate);
    }
    w.line("spray.element.zone", zone);
    w.line("spray.element.drying", drying);
    w.line("spray.element.t_in", t_in);
    w.line("spray.element.mu_wet", mu_wet);
    w.line("spray.element.t_wet", t_wet);
    w.line("spray.element.rate", rate);
  }
}

Drive read_drive(CheckpointReader& r, const Model& m) {
  Drive d;
  d.restart_time = r.line_num("restart_time");
  for (const Pulley& pl : m.pulleys) {
    PulleyDrive& p = d.pulleys.emplace_back();
    if (r.line_str("pulley.drive") != pl.name) r.fail("expected the drive of pulley '" + pl.name + "'");
    p.kinematic = r.line_choice("pulley.drive.by", {"torque", "speed"}) == 1;
    const std::string label = "pulley '" + pl.name + "'";
    p.torque = read_law(r, "pulley.torque");
    checked(r, [&] { validate_law(label + ".torque", p.torque, false); });
    p.speed = read_law(r, "pulley.speed");
    checked(r, [&] { validate_law(label + ".speed", p.speed, true); });
  }
  const size_t n = static_cast<size_t>(m.n_el());
  d.mu = r.line_doubles("belt.mu", n);
  if (d.mu.size() != n) r.fail(std::to_string(d.mu.size()) + " values for " + std::to_string(n) + " elements");
  checked(r, [&] {
    for (size_t i = 0; i < n; ++i) require_mu("belt.mu of element " + std::to_string(i), d.mu[i]);
  });
  if (r.next_is("spray")) {
    Spray& sp = d.spray;
    r.open("spray");
    const size_t nz = r.group_count(4);
    r.close();
    for (size_t k = 0; k < nz; ++k) {
      SprayZone& z = sp.zones.emplace_back();
      const std::vector<double> c = r.line_fixed("spray.centre", 2);
      z.centre = Vec2(c[0], c[1]);
      r.open("spray.zone");
      z.radius = r.num(), z.mu = r.num(), z.from = r.num(), z.to = r.num_or_infinity(), z.drying_length = r.num();
      r.close();
      z.enabled = r.line_bool("spray.enabled");
      z.on = r.line_bool("spray.on");
    }
    const std::vector<int> zone = r.line_ints("spray.element.zone", -1, static_cast<long>(nz) - 1, n);
    const std::vector<int> drying = r.line_ints("spray.element.drying", 0, 1, n);
    const std::vector<double> t_in = r.line_doubles("spray.element.t_in", n);
    const std::vector<double> mu_wet = r.line_doubles("spray.element.mu_wet", n);
    const std::vector<double> t_wet = r.line_doubles("spray.element.t_wet", n);
    const std::vector<double> rate = r.line_doubles("spray.element.rate", n);
    for (const auto* v : {&t_in, &mu_wet, &t_wet, &rate})
      if (v->size() != n) r.fail(std::to_string(v->size()) + " values for " + std::to_string(n) + " elements");
    if (zone.size() != n || drying.size() != n) r.fail("one value per element expected");
    sp.el.resize(n);
    for (size_t i = 0; i < n; ++i) {
      ElementSpray& e = sp.el[i];
      e.zone = zone[i], e.drying = drying[i] != 0 && zone[i] < 0;
      e.t_in = t_in[i], e.mu_wet = mu_wet[i], e.t_wet = t_wet[i], e.rate = rate[i];
      if (!(e.mu_wet >= 0) || !(e.rate >= 0)) r.fail("element " + std::to_string(i) + ": μ and rate must be >= 0");
      if (e.zone >= 0 || e.drying) sp.n_wet++;
    }
  }
  return d;
}

// ---- the scene -----------------------------------------------------------------------------

void write_scene(CheckpointWriter& w, const Scene& sc) {
  const Model& m = sc.model;
  w.line("pulleys", m.n_p());
  for (const Pulley& p : m.pulleys) {
    w.line("pulley.name", p.name);
    w.fixed("pulley.centre", {p.centre.x(), p.centre.y()});
    w.line("pulley.radius", p.radius);
    w.line("pulley.inertia", p.inertia);
    w.word("pulley.wrap", p.wrap == WrapSide::back ? "back" : "inside");
  }
  if (!m.arms.empty()) {  // only a scene with tensioner arms has this part
    w.line("arms", m.n_arm());
    for (const Arm& a : m.arms) {
      w.line("arm.pulley", a.pulley);
      w.fixed("arm.pivot", {a.pivot.x(), a.pivot.y()});
      w.line("arm.length", a.length);
      w.line("arm.inertia", a.inertia);
      w.line("arm.stiffness", a.stiffness);
      w.line("arm.free_angle", a.free_angle);
      w.line("arm.damping", a.damping);
      w.line("arm.friction_torque", a.friction_torque);
      w.line("arm.friction_speed", a.friction_speed);
      w.line("arm.asymmetric", a.asymmetric);
      w.line("arm.press", a.press);
    }
  }
  if (!m.couplings.empty()) {  // only a scene with coupled rotors has this part
    w.line("couplings", m.n_coupling());
    for (const Coupling& c : m.couplings) {
      w.line("coupling.pulley", c.pulley);
      w.line("coupling.inertia", c.inertia);
      w.line("coupling.stiffness", c.stiffness);
      w.line("coupling.damping", c.damping);
      w.line("coupling.one_way", c.one_way ? 1 : 0);
      w.line("coupling.sense", c.sense);
      w.line("coupling.hub_inertia", c.hub_inertia);
      w.line("coupling.lock_damping", c.lock_damping);
      w.line("coupling.drag_torque", c.drag_torque);
    }
  }
  const Belt& b = m.belt;
  w.line("belt.elements", b.n);
  w.line("belt.pitch", b.pitch);
  w.line("belt.rigid_length", b.rigid_length);
  w.line("belt.mass", b.mass);
  w.line("belt.rot_inertia", b.rot_inertia);
  w.line("belt.sde.k", b.k);
  w.line("belt.sde.c", b.c);
  w.line("belt.sde.kt", b.kt);
  w.line("belt.sde.ct", b.ct);
  w.line("belt.e_tra", b.e_tra);
  w.line("belt.e_tor", b.e_tor);
  w.line("contact.c1", m.contact.c1);
  w.line("contact.c2", m.contact.c2);
  w.line("contact.damping", m.contact.b);
  w.line("contact.p_max", m.contact.p_max);
  write_friction(w, "friction.", m.friction);
  // the segments' laws, then each element's (0: the scene's)
  w.line("friction.segments", static_cast<long>(m.laws.size()));
  for (const Friction& f : m.laws) write_friction(w, "segment.", f);
  w.line("segment.law_of", std::vector<int>(m.law_of.begin(), m.law_of.end()));
  w.line("gravity", m.gravity);
  w.line("energy", m.track_energy);
  write_drive(w, m, sc.drive);
  w.line("y0", sc.y0.data(), static_cast<size_t>(sc.y0.size()));
  write_route(w, sc.route);
  w.line("route.names", sc.route_names);
  w.line("route.pulleys", sc.route_pulleys);
  w.line("penetration", sc.penetration);
  w.word("reading", sc.reading == StiffnessReading::per_sde ? "per_sde" : "rigidity");
  w.line("inputs", static_cast<long>(sc.inputs.size()));
  for (const SceneInput& e : sc.inputs) {
    w.line("input.name", e.name);
    w.line("input.value", e.value);
    w.line("input.text", e.text);
    w.line("input.given", e.given);
  }
  w.line("static_tension", sc.static_tension);
  w.line("static_residual", sc.static_residual);
  w.line("static_retried", sc.static_retried);
  w.line("span_sde", sc.span_sde);
  w.line("sites", static_cast<long>(sc.sites.size()));
  for (const ElementSite& e : sc.sites) {
    w.line("site.index", e.index);
    w.fixed("site.centre", {e.centre.x(), e.centre.y()});
    w.line("site.s", e.s);
    w.line("site.length", e.length);
    w.line("site.pulley", e.pulley);
    w.line("site.meets", e.meets);
    w.line("site.leaves", e.leaves);
  }
}

namespace {

void read_pulleys(CheckpointReader& r, Model& m) {
  r.open("pulleys");
  const size_t np = r.group_count(5);
  r.close();
  for (size_t j = 0; j < np; ++j) {
    Pulley& p = m.pulleys.emplace_back();
    p.name = r.line_str("pulley.name");
    p.centre = read_vec2(r, "pulley.centre");
    p.radius = r.line_num("pulley.radius");
    p.inertia = r.line_num("pulley.inertia");
    p.wrap = r.line_choice("pulley.wrap", {"inside", "back"}) == 1 ? WrapSide::back : WrapSide::inside;
  }
}

void read_arms(CheckpointReader& r, Model& m) {
  if (!r.next_is("arms")) return;
  const size_t np = m.pulleys.size();
  r.open("arms");
  const size_t na = r.group_count(11, np);
  r.close();
  for (size_t k = 0; k < na; ++k) {
    Arm& a = m.arms.emplace_back();
    a.pulley = static_cast<int>(r.line_int("arm.pulley", 0, static_cast<long>(np) - 1));
    if (m.pulleys[a.pulley].arm >= 0) r.fail("pulley " + std::to_string(a.pulley) + " has an arm already");
    m.pulleys[a.pulley].arm = static_cast<int>(k);
    a.pivot = read_vec2(r, "arm.pivot");
    a.length = r.line_num("arm.length");
    a.inertia = r.line_num("arm.inertia");
    a.stiffness = r.line_num("arm.stiffness");
    a.free_angle = r.line_num("arm.free_angle");
    a.damping = r.line_num("arm.damping");
    a.friction_torque = r.line_num("arm.friction_torque");
    a.friction_speed = r.line_num("arm.friction_speed");
    a.asymmetric = r.line_num("arm.asymmetric");
    a.press = static_cast<int>(r.line_int("arm.press", -1, 1));
    checked(r, [&] { require_positive("arm.length", a.length, "m"); });
  }
}

void read_couplings(CheckpointReader& r, Model& m) {
  if (!r.next_is("couplings")) return;
  const size_t np = m.pulleys.size();
  r.open("couplings");
  const size_t nc = r.group_count(9, np);
  r.close();
  int coord = 0;
  for (size_t k = 0; k < nc; ++k) {
    Coupling& c = m.couplings.emplace_back();
    c.pulley = static_cast<int>(r.line_int("coupling.pulley", 0, static_cast<long>(np) - 1));
    if (m.pulleys[c.pulley].coupling >= 0) r.fail("pulley " + std::to_string(c.pulley) + " has a coupling already");
    m.pulleys[c.pulley].coupling = static_cast<int>(k);
    c.inertia = r.line_num("coupling.inertia");
    c.stiffness = r.line_num("coupling.stiffness");
    c.damping = r.line_num("coupling.damping");
    c.one_way = r.line_int("coupling.one_way", 0, 1) == 1;
    c.sense = static_cast<int>(r.line_int("coupling.sense", -1, 1));
    if (c.sense == 0) r.fail("coupling.sense must be -1 or 1");
    c.hub_inertia = r.line_num("coupling.hub_inertia");
    c.lock_damping = r.line_num("coupling.lock_damping");
    c.drag_torque = r.line_num("coupling.drag_torque");
    c.coord = coord;
    coord += c.one_way ? 2 : 1;
  }
}

// the belt, the contact, the friction laws (the scene's and the segments') and the rest of the model
void read_belt(CheckpointReader& r, Model& m) {
  Belt& b = m.belt;
  b.n = static_cast<int>(r.line_int("belt.elements", 0, INT_MAX / 8));
  b.pitch = r.line_num("belt.pitch");
  b.rigid_length = r.line_num("belt.rigid_length");
  b.mass = r.line_num("belt.mass");
  b.rot_inertia = r.line_num("belt.rot_inertia");
  b.k = r.line_num("belt.sde.k");
  b.c = r.line_num("belt.sde.c");
  b.kt = r.line_num("belt.sde.kt");
  b.ct = r.line_num("belt.sde.ct");
  b.e_tra = r.line_num("belt.e_tra");
  b.e_tor = r.line_num("belt.e_tor");
  m.contact.c1 = r.line_num("contact.c1");
  m.contact.c2 = r.line_num("contact.c2");
  m.contact.b = r.line_num("contact.damping");
  m.contact.p_max = r.line_num("contact.p_max");
  m.friction = read_friction(r, "friction.");
  r.open("friction.segments");
  const size_t n_laws = r.group_count(kFrictionLines, kMaxFrictionSegments);
  r.close();
  for (size_t k = 0; k < n_laws; ++k) {
    m.laws.push_back(read_friction(r, "segment."));
    checked(r, [&] { check_friction_law(m.laws.back(), "friction.segments[" + std::to_string(k + 1) + "]"); });
  }
  const std::vector<int> law_of = r.line_ints("segment.law_of", 0, static_cast<long>(n_laws), static_cast<size_t>(b.n));
  if (!(law_of.empty() ? n_laws == 0 : law_of.size() == static_cast<size_t>(b.n)))
    r.fail(std::to_string(law_of.size()) + " laws for " + std::to_string(b.n) + " elements and " +
           std::to_string(n_laws) + " segments");
  m.law_of.assign(law_of.begin(), law_of.end());
  m.gravity = r.line_num("gravity");
  m.track_energy = r.line_bool("energy");
}

// the route round the pulleys, the penetrations and the stiffness reading
void read_placement(CheckpointReader& r, Scene& sc) {
  const Model& m = sc.model;
  const size_t np = m.pulleys.size();
  sc.route = read_route(r, np);
  sc.route_names = r.line_strs("route.names", np);
  sc.route_pulleys = r.line_ints("route.pulleys", 0, static_cast<long>(np) - 1, np);
  if (sc.route_names.size() != np || sc.route_pulleys.size() != np) r.fail("one entry per pulley expected");
  for (size_t k = 0; k < np; ++k)
    if (m.pulleys[static_cast<size_t>(sc.route_pulleys[k])].name != sc.route_names[k])
      r.fail("entry " + std::to_string(k + 1) + " is not pulley '" + sc.route_names[k] + "'");
  sc.penetration = r.line_doubles("penetration", np);
  if (sc.penetration.size() != np) r.fail("one value per pulley expected");
  sc.reading = r.line_choice("reading", {"rigidity", "per_sde"}) == 1 ? StiffnessReading::per_sde
                                                                       : StiffnessReading::rigidity;
}

void read_inputs(CheckpointReader& r, Scene& sc) {
  r.open("inputs");
  const size_t n_inputs = r.group_count(4);
  r.close();
  for (size_t i = 0; i < n_inputs; ++i) {
    const std::string name = r.line_str("input.name");
    const Parameter* par = input_parameter(name, sc.model);
    if (!par) r.fail("'" + name + "' is not a scene parameter");
    const double value = r.line_num("input.value");
    const std::string text = r.line_str("input.text");
    sc.inputs.push_back(scene_input(*par, name, value, text, r.line_bool("input.given")));
  }
}

// the static solve's figures, the span SDEs and each element's initial site
void read_sites(CheckpointReader& r, Scene& sc) {
  const size_t np = sc.model.pulleys.size();
  const int n = sc.model.belt.n;
  sc.static_tension = r.line_num("static_tension");
  sc.static_residual = r.line_num("static_residual");
  sc.static_retried = r.line_bool("static_retried");
  sc.span_sde = r.line_ints("span_sde", 0, n - 1L, np);
  if (sc.span_sde.size() != np) r.fail("one element per span expected");
  r.open("sites");
  const size_t n_sites = r.group_count(7, static_cast<size_t>(n));
  if (n_sites != static_cast<size_t>(n)) r.fail(std::to_string(n_sites) + " for " + std::to_string(n) + " elements");
  r.close();
  for (size_t i = 0; i < n_sites; ++i) {
    ElementSite& e = sc.sites.emplace_back();
    e.index = static_cast<int>(r.line_int("site.index", static_cast<long>(i), static_cast<long>(i)));
    e.centre = read_vec2(r, "site.centre");
    e.s = r.line_num("site.s");
    e.length = r.line_num("site.length");
    e.pulley = r.line_str("site.pulley");
    e.meets = r.line_map("site.meets", np);
    e.leaves = r.line_map("site.leaves", np);
  }
}

// the scene read is checked as a script's scene is, with what the build derives from it; an
// error names the scene's lines, from `first`
void check_read_scene(CheckpointReader& r, const Scene& sc, int first) {
  const Belt& b = sc.model.belt;
  std::string error;
  try {
    require_positive("belt.pitch", b.pitch, "m");
    require_positive("belt.rigid_length", b.rigid_length, "m");
    require_positive("belt.mass", b.mass, "kg");
    require_positive("belt.rot_inertia", b.rot_inertia, "kg·m²");
    const SceneDef def = definition(sc);
    validate(def);
    for (const PulleyDef& p : def.pulleys) build::validate_tensioner(p), build::validate_coupling(p);
  } catch (const ParameterError& e) {
    error = e.what();
  }
  if (!error.empty()) r.fail_lines(first, "the scene: " + error);
}

}  // namespace

Scene read_scene(CheckpointReader& r) {
  const int first = r.line_number() + 1;
  Scene sc;
  Model& m = sc.model;
  read_pulleys(r, m);
  read_arms(r, m);
  read_couplings(r, m);
  read_belt(r, m);
  sc.drive = read_drive(r, m);
  const size_t n_state = static_cast<size_t>(m.n_state());
  const std::vector<double> y0 = r.line_doubles("y0", n_state);
  if (y0.size() != n_state) r.fail(std::to_string(y0.size()) + " values for a state of " + std::to_string(n_state));
  sc.y0 = Eigen::Map<const Eigen::VectorXd>(y0.data(), static_cast<Eigen::Index>(y0.size()));
  read_placement(r, sc);
  read_inputs(r, sc);
  read_sites(r, sc);
  check_read_scene(r, sc, first);
  return sc;
}

}  // namespace beltsim
