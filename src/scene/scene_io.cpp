#include "scene/scene_io.hpp"

#include <climits>
#include <cmath>

#include "scene/build.hpp"
#include "scene/field_io.hpp"
#include "scene/scene_fields.hpp"
#include "scene/validate.hpp"

namespace beltsim {

namespace {

using fields::get_list;
using fields::put_list;

// a ParameterError (the validation's reason and value) as a CheckpointError naming the line that
// last opened with `key`
template <class F>
void checked(CheckpointReader& r, const std::string& key, F&& f) {
  std::string error;
  try {
    f();
  } catch (const ParameterError& e) {
    error = e.what();
  }
  if (!error.empty()) r.fail_at(r.line_of(key), key, error);
}

// the same naming the lines from `first` to the one just read, the message after `part`
template <class F>
void checked_lines(CheckpointReader& r, int first, F&& f, const std::string& part = "") {
  std::string error;
  try {
    f();
  } catch (const ParameterError& e) {
    error = e.what();
  }
  if (!error.empty()) r.fail_lines(first, part + error);
}

// a count read at `key` that must be `n`: "2 values for 60 elements"
void one_each(CheckpointReader& r, const std::string& key, size_t got, size_t n, const char* what, const char* each) {
  if (got != n)
    r.fail_at(r.line_of(key), key, std::to_string(got) + " " + what + " for " + std::to_string(n) + " " + each);
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

// ---- the definition a scene gives back ---------------------------------------------------------

#define BELTSIM_COPY(kind, member, key, unit) to.member = from.member;
#define BELTSIM_SKIP(kind, member, key, unit)

namespace {

void copy(const Pulley& from, PulleyDef& to) {
  BELTSIM_PULLEY_FIELDS(BELTSIM_COPY, BELTSIM_SKIP)
}
void copy(const Arm& from, TensionerDef& to) {
  BELTSIM_ARM_FIELDS(BELTSIM_COPY, BELTSIM_SKIP)
}
void copy(const Coupling& from, CouplingDef& to) {
  BELTSIM_COUPLING_FIELDS(BELTSIM_COPY, BELTSIM_SKIP)
}
void copy(const Belt& from, BeltDef& to) {
  BELTSIM_BELT_FIELDS(BELTSIM_COPY, BELTSIM_SKIP)
}
void copy(const PulleyDrive& from, PulleyDef& to) {
  BELTSIM_PULLEY_DRIVE_FIELDS(BELTSIM_COPY, BELTSIM_SKIP)
}

}  // namespace

SceneDef definition(const Scene& sc) {
  const Model& m = sc.model;
  SceneDef d;
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& p = m.pulleys[j];
    PulleyDef& pd = d.pulleys.emplace_back();
    copy(p, pd);
    copy(sc.drive.pulleys[j], pd);
    if (p.arm >= 0) copy(m.arms[p.arm], pd.tensioner.emplace());
    if (p.coupling >= 0) {
      CouplingDef& c = pd.coupling.emplace();
      copy(m.couplings[p.coupling], c);
      // a two-way coupling has no clutch hub: its model holds zeros there, which the rules of a
      // one-way coupling's hub refuse (a user's trial could not resume a two-way decoupler's
      // checkpoint: "hub_inertia must be > 0 (got 0)"); the scene's defaults stand in, unused
      if (!c.one_way) {
        const CouplingDef unused;
        c.hub_inertia = unused.hub_inertia, c.lock_damping = unused.lock_damping, c.drag_torque = unused.drag_torque;
      }
    }
  }
  BeltDef& b = d.belt;
  copy(m.belt, b);  // per SDE, as built
  b.reading = StiffnessReading::per_sde;
  b.elements = m.belt.n;
  b.tensioning = Tensioning::rest_length;
  b.rest_length = m.belt.rigid_length * m.belt.n;
  b.mass_per_length = m.belt.mass / m.belt.rigid_length;  // the build's m = ρ·l0 (build::set_rest_length)
  b.route = sc.route_names;
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
  fields::put_own(w, d);
  for (int j = 0; j < m.n_p(); ++j) {
    w.line("pulley.drive", m.pulleys[j].name);
    fields::put(w, "pulley.", d.pulleys[j]);
  }
  if (d.spray.any()) {  // only a drive with spray zones has this part
    put_list(w, "spray", "spray.", d.spray.zones);
    fields::put(w, "spray.element.", d.spray.el);
  }
}

namespace {

// the zones, then each element's record: a zone's number or -1, μ and rate >= 0
void read_spray(CheckpointReader& r, size_t n, Spray& sp) {
  get_list(r, "spray", "spray.", sp.zones);
  fields::get(r, "spray.element.", n, sp.el);
  const long nz = static_cast<long>(sp.zones.size());
  for (size_t i = 0; i < n; ++i) {
    ElementSpray& e = sp.el[i];
    const std::string el = "element " + std::to_string(i) + ": ";
    if (e.zone < -1 || e.zone >= nz)
      r.fail_at(r.line_of("spray.element.zone"), "spray.element.zone",
                el + std::to_string(e.zone) + " is not a zone (-1 to " + std::to_string(nz - 1) + ")");
    e.drying = e.drying && e.zone < 0;
    if (!(e.mu_wet >= 0)) r.fail_at(r.line_of("spray.element.mu_wet"), "spray.element.mu_wet", el + "μ must be >= 0");
    if (!(e.rate >= 0)) r.fail_at(r.line_of("spray.element.rate"), "spray.element.rate", el + "the rate must be >= 0");
    if (e.zone >= 0 || e.drying) sp.n_wet++;
  }
}

}  // namespace

Drive read_drive(CheckpointReader& r, const Model& m) {
  Drive d;
  fields::get_own(r, d);
  const size_t n = static_cast<size_t>(m.n_el());
  one_each(r, "belt.mu", d.mu.size(), n, "values", "elements");
  checked(r, "belt.mu", [&] {
    for (size_t i = 0; i < n; ++i) require_mu("belt.mu of element " + std::to_string(i), d.mu[i]);
  });
  for (const Pulley& pl : m.pulleys) {
    if (r.line_str("pulley.drive") != pl.name) r.fail("expected the drive of pulley '" + pl.name + "'");
    const int first = r.line_number();
    PulleyDrive& p = d.pulleys.emplace_back();
    fields::get(r, "pulley.", p);
    const std::string label = "pulley '" + pl.name + "'";
    checked_lines(r, first, [&] {
      validate_law(label + ".torque", p.torque, false);
      validate_law(label + ".speed", p.speed, true);
    });
  }
  if (r.next_is("spray")) read_spray(r, n, d.spray);
  return d;
}

std::string drive_difference(const Drive& a, const Drive& b) {
  std::string d;
  auto differs = [&](std::string s) { return !(d = std::move(s)).empty(); };
  if (differs(fields::difference_own(a, b)) || differs(fields::difference_list("pulley.", a.pulleys, b.pulleys)) ||
      differs(fields::difference_list("spray.", a.spray.zones, b.spray.zones)) ||
      differs(fields::difference("spray.element.", a.spray.el, b.spray.el)))
    return d;
  return a.spray.n_wet == b.spray.n_wet ? "" : "spray.n_wet";
}

// ---- the scene -----------------------------------------------------------------------------

void write_scene(CheckpointWriter& w, const Scene& sc) {
  const Model& m = sc.model;
  put_list(w, "pulleys", "pulley.", m.pulleys);
  if (!m.arms.empty()) put_list(w, "arms", "arm.", m.arms);  // only a scene with tensioner arms has these parts
  if (!m.couplings.empty()) put_list(w, "couplings", "coupling.", m.couplings);  // ... and with coupled rotors
  fields::put(w, "belt.", m.belt);
  fields::put(w, "contact.", m.contact);
  fields::put(w, "friction.", m.friction);
  // the segments' laws, then each element's (0: the scene's)
  put_list(w, "friction.segments", "segment.", m.laws);
  w.line("segment.law_of", std::vector<int>(m.law_of.begin(), m.law_of.end()));
  fields::put_own(w, m);
  write_drive(w, m, sc.drive);
  w.line("y0", sc.y0.data(), static_cast<size_t>(sc.y0.size()));
  put_list(w, "route.spans", "span.", sc.route.spans);
  put_list(w, "route.arcs", "arc.", sc.route.arcs);
  w.line("route.length", sc.route.length);
  fields::put_own(w, sc);
  put_list(w, "inputs", "input.", sc.inputs);
  put_list(w, "sites", "site.", sc.sites);
}

namespace {

// the pulleys, the arms and couplings on them (each on a pulley of its own), the belt, the contact,
// the friction laws (the scene's and the segments') and the rest of the model
void read_model(CheckpointReader& r, Model& m) {
  get_list(r, "pulleys", "pulley.", m.pulleys);
  const long np = m.n_p();
  auto on_pulley = [&](const std::string& key, int j, int Pulley::*slot, size_t k) {
    if (j < 0 || j >= np)
      r.fail_at(r.line_of(key), key, std::to_string(j) + " is not a pulley (0 to " + std::to_string(np - 1) + ")");
    if (m.pulleys[j].*slot >= 0) r.fail_at(r.line_of(key), key, "pulley " + std::to_string(j) + " has one already");
    m.pulleys[j].*slot = static_cast<int>(k);
  };
  if (r.next_is("arms"))
    get_list(r, "arms", "arm.", m.arms, np, [&](size_t k, Arm& a) {
      on_pulley("arm.pulley", a.pulley, &Pulley::arm, k);
      checked(r, "arm.length", [&] { require_positive("arm.length", a.length, "m"); });
    });
  int coord = 0;
  if (r.next_is("couplings"))
    get_list(r, "couplings", "coupling.", m.couplings, np, [&](size_t k, Coupling& c) {
      on_pulley("coupling.pulley", c.pulley, &Pulley::coupling, k);
      if (c.sense == 0) r.fail_at(r.line_of("coupling.sense"), "coupling.sense", "must be -1 or 1");
      c.coord = coord;
      coord += c.one_way ? 2 : 1;
    });
  fields::get(r, "belt.", m.belt);
  if (m.belt.n < 0 || m.belt.n > INT_MAX / 8)
    r.fail_at(r.line_of("belt.elements"), "belt.elements", std::to_string(m.belt.n) + " is not an element count");
  fields::get(r, "contact.", m.contact);
  fields::get(r, "friction.", m.friction);
  get_list(r, "friction.segments", "segment.", m.laws, kMaxFrictionSegments, [&](size_t k, const Friction& f) {
    checked_lines(r, r.line_number() + 1 - static_cast<int>(fields::lines(&f)),
                  [&] { check_friction_law(f, "friction.segments[" + std::to_string(k + 1) + "]"); });
  });
  const size_t n = static_cast<size_t>(m.belt.n), n_laws = m.laws.size();
  const std::vector<int> law_of = r.line_ints("segment.law_of", 0, static_cast<long>(n_laws), n);
  if (!(law_of.empty() ? n_laws == 0 : law_of.size() == n))
    r.fail(std::to_string(law_of.size()) + " laws for " + std::to_string(n) + " elements and " +
           std::to_string(n_laws) + " segments");
  m.law_of.assign(law_of.begin(), law_of.end());
  fields::get_own(r, m);
}

// the route round the pulleys, the scene's own fields (the route's order, the penetrations, the
// stiffness reading, the static solve's figures), its inputs and each element's initial site
void read_placement(CheckpointReader& r, Scene& sc) {
  const Model& m = sc.model;
  const size_t np = m.pulleys.size();
  get_list(r, "route.spans", "span.", sc.route.spans, np);
  one_each(r, "route.spans", sc.route.spans.size(), np, "spans", "pulleys");
  get_list(r, "route.arcs", "arc.", sc.route.arcs, np);
  one_each(r, "route.arcs", sc.route.arcs.size(), np, "arcs", "pulleys");
  sc.route.length = r.line_num("route.length");
  fields::get_own(r, sc);
  one_each(r, "route.names", sc.route_names.size(), np, "names", "pulleys");
  one_each(r, "route.pulleys", sc.route_pulleys.size(), np, "entries", "pulleys");
  for (size_t k = 0; k < np; ++k) {
    const int j = sc.route_pulleys[k];
    if (j < 0 || j >= static_cast<int>(np) || m.pulleys[static_cast<size_t>(j)].name != sc.route_names[k])
      r.fail_at(r.line_of("route.pulleys"), "route.pulleys",
                "entry " + std::to_string(k + 1) + " is not pulley '" + sc.route_names[k] + "'");
  }
  one_each(r, "penetration", sc.penetration.size(), np, "values", "pulleys");
  get_list(r, "inputs", "input.", sc.inputs, SIZE_MAX, [&](size_t, SceneInput& e) {
    const Parameter* par = input_parameter(e.name, m);
    if (!par) r.fail_at(r.line_of("input.name"), "input.name", "'" + e.name + "' is not a scene parameter");
    e = scene_input(*par, e.name, e.value, e.text, e.given);
  });
  mark_derived(sc.inputs);
  get_list(r, "sites", "site.", sc.sites, static_cast<size_t>(m.n_el()), [&](size_t i, const ElementSite& e) {
    if (e.index != static_cast<int>(i))
      r.fail_at(r.line_of("site.index"), "site.index", "element " + std::to_string(i) + " expected");
    for (const auto& [key, places] : {std::pair{"site.meets", &e.meets}, {"site.leaves", &e.leaves}})
      if (places->size() > np)
        r.fail_at(r.line_of(key), key, "more places than the " + std::to_string(np) + " pulleys");
  });
  one_each(r, "sites", sc.sites.size(), static_cast<size_t>(m.n_el()), "sites", "elements");
}

// (the belt's derived lengths, mass and inertia > 0)
void positive_real(const std::string& key, double v, const char* unit) {
  require_positive(key, v, unit);
}
void positive_integer(const std::string&, int, const char*) {}
#define BELTSIM_POSITIVE(kind, member, key, unit) positive_##kind("belt." key, b.member, unit);

// the scene read is checked as a script's scene is, with what the build derives from it; an
// error names the scene's lines, from `first`
void check_read_scene(CheckpointReader& r, const Scene& sc, int first) {
  const Belt& b = sc.model.belt;
  checked_lines(
      r, first,
      [&] {
        BELTSIM_BELT_FIELDS(BELTSIM_SKIP, BELTSIM_POSITIVE)
        const SceneDef def = definition(sc);
        validate(def);
        for (const PulleyDef& p : def.pulleys) build::validate_tensioner(p), build::validate_coupling(p);
      },
      "the scene: ");
}

}  // namespace

Scene read_scene(CheckpointReader& r) {
  const int first = r.line_number() + 1;
  Scene sc;
  Model& m = sc.model;
  read_model(r, m);
  sc.drive = read_drive(r, m);
  const size_t n_state = static_cast<size_t>(m.n_state());
  const std::vector<double> y0 = r.line_doubles("y0", n_state);
  one_each(r, "y0", y0.size(), n_state, "values", "components of the state");
  sc.y0 = Eigen::Map<const Eigen::VectorXd>(y0.data(), static_cast<Eigen::Index>(y0.size()));
  read_placement(r, sc);
  check_read_scene(r, sc, first);
  return sc;
}

std::string scene_difference(const Scene& a, const Scene& b) {
  const Model &ma = a.model, &mb = b.model;
  std::string d;
  auto differs = [&](std::string s) { return !(d = std::move(s)).empty(); };
  using fields::difference;
  using fields::difference_list;
  if (differs(difference_list("pulley.", ma.pulleys, mb.pulleys)) ||
      differs(difference_list("arm.", ma.arms, mb.arms)) ||
      differs(difference_list("coupling.", ma.couplings, mb.couplings)) ||
      differs(difference("belt.", ma.belt, mb.belt)) || differs(difference("contact.", ma.contact, mb.contact)) ||
      differs(difference("friction.", ma.friction, mb.friction)) ||
      differs(difference_list("segment.", ma.laws, mb.laws)) ||
      differs(ma.law_of == mb.law_of ? "" : "segment.law_of") || differs(fields::difference_own(ma, mb)) ||
      differs(drive_difference(a.drive, b.drive)) || differs(fields::same_value(a.y0, b.y0) ? "" : "y0") ||
      differs(difference_list("span.", a.route.spans, b.route.spans)) ||
      differs(difference_list("arc.", a.route.arcs, b.route.arcs)) ||
      differs(fields::same_value(a.route.length, b.route.length) ? "" : "route.length") ||
      differs(fields::difference_own(a, b)) || differs(difference_list("input.", a.inputs, b.inputs)) ||
      differs(difference_list("site.", a.sites, b.sites)))
    return d;
  return "";
}

}  // namespace beltsim
