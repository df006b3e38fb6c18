#include "model/observables.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "model/block_matrix.hpp"
#include "model/contacts.hpp"
#include "model/forces.hpp"

namespace beltsim {

const char* contact_state_name(ContactState s) {
  switch (s) {
    case ContactState::stick: return "stick";
    case ContactState::slip: return "slip";
    default: return "free";
  }
}

namespace {
// the elements' settling onto the rim where the belt runs on: saturated runs of at most this many
// elements off the gross-slip arc stick (observables.hpp)
constexpr int kSettlingElements = 3;

// the sums of element contacts over the pairs of a contact stage
struct PairSums {
  std::vector<ElementContact>& el;  // indexed by element, first..first+size
  int first;
  std::vector<double> deepest;
  PairSums(std::vector<ElementContact>& e, int first_el) : el(e), first(first_el), deepest(e.size(), 0.0) {
    for (ElementContact& c : el) c = ElementContact{}, c.slip = std::numeric_limits<double>::quiet_NaN();
  }
  void add(const ContactPair& c) {
    ElementContact& e = el[c.i - first];
    e.normal += c.nl.N;
    e.friction -= c.fl.mu_eff * c.nl.N;
    if (c.nl.p > deepest[c.i - first]) {
      deepest[c.i - first] = c.nl.p;
      e.pulley = c.j;
      e.slip = c.fl.vT;
      e.penetration = c.nl.p;
    }
  }
};

// the belt's moment on pulley j and its hub load from the pulley's pairs
double pulley_load(const ContactView& pairs, int j, Vec2* hub_load) {
  double moment = 0;
  Vec2 load = Vec2::Zero();
  for (const ContactPair& c : pairs) {
    if (c.j != j || !c.touching || !c.nl.pushing) continue;
    const NormalLaw& nl = c.nl;
    moment += nl.r * c.fl.mu_eff * nl.N;
    load -= nl.N * nl.n - c.fl.mu_eff * nl.N * nl.t;  // reaction of the force on the element
  }
  if (hub_load) *hub_load = load;
  return moment;
}

// element i with its contact sums and the axial forces of its two SDEs (i joins it to i-1, next
// to i+1) given
ElementObs element_with(const Drive& d, const std::vector<int>& sense, double t, const double* y, int i,
                        const ElementContact& c, double sde_force, double next_force) {
  const double* q = y;
  ElementObs o;
  o.x = q[3 * i], o.y = q[3 * i + 1], o.phi = q[3 * i + 2];
  o.sde_force = sde_force;
  o.tension = 0.5 * (sde_force + next_force);
  o.mu = d.mu_at(i, t);
  o.normal = c.normal;
  o.pulley = c.pulley;
  if (c.pulley < 0 || !(c.normal > 0)) {
    o.friction = o.slip = std::numeric_limits<double>::quiet_NaN();
    o.state = ContactState::free;
    return o;
  }
  // t̂ is anticlockwise; the belt travels along sense·t̂ on this pulley
  const int s = sense[c.pulley];
  o.friction = s * c.friction;
  o.slip = s * c.slip;
  o.penetration = c.penetration;
  o.state = ContactState::stick;  // which arc: classify_contact
  return o;
}

PulleyObs pulley_with(const Model& m, const Drive& d, double t, const double* y, int j, const ContactView& pairs) {
  const double* q = y;
  const double* v = y + m.n_coord();
  PulleyObs o;
  o.omega = d.omega(m, j, t, v);
  o.angle = q[m.pulley_coord(j)];
  o.belt_torque = pulley_load(pairs, j, &o.hub);
  o.hub_load = o.hub.norm();
  o.torque = d.kinematic(j) ? m.pulleys[j].inertia * d.speed_rate(j, t) - o.belt_torque : applied_torque(m, d, t, v, j);
  const int a = m.pulleys[j].arm;
  o.arm_angle = a >= 0 ? q[m.arm_coord(a)] : std::numeric_limits<double>::quiet_NaN();
  o.arm_rate = a >= 0 ? v[m.arm_coord(a)] : std::numeric_limits<double>::quiet_NaN();
  const int c = m.pulleys[j].coupling;
  if (c >= 0) {
    const CouplingState s = coupling_state(m, d, t, q, v, c);
    o.rotor_angle = s.rotor_angle, o.rotor_speed = s.rotor_speed, o.windup = s.windup;
    o.coupling_torque = s.transmitted;
  } else {
    o.rotor_angle = o.rotor_speed = o.windup = o.coupling_torque = std::numeric_limits<double>::quiet_NaN();
  }
  return o;
}
}  // namespace

ElementContact element_contact(const ContactRecords& contacts, int i) {
  std::vector<ElementContact> one(1);
  PairSums sums(one, i);
  for (const ContactPair& c : contacts.pairs())
    if (c.i == i) sums.add(c);
  return one[0];
}

double belt_torque(const ContactRecords& contacts, int j, Vec2* hub_load) {
  return pulley_load(contacts.pairs(), j, hub_load);
}

PulleyObs observe_pulley(const Model& m, const Drive& d, double t, const double* y, const ContactRecords& contacts,
                         int j) {
  assert(contacts.of(m, t, y));
  return pulley_with(m, d, t, y, j, contacts.pairs());
}

void observe_pulleys(const Model& m, const Drive& d, double t, const double* y, ContactRecords& contacts,
                     std::vector<PulleyObs>& out) {
  fill_contacts(m, d, t, y, contacts);
  out.resize(m.n_p());
  for (int j = 0; j < m.n_p(); ++j) out[j] = pulley_with(m, d, t, y, j, contacts.pairs());
}

void observe(const Model& m, const Drive& d, const std::vector<int>& sense, double t, const double* y,
             Observation& out) {
  const int n = m.n_el();
  out.t = t;
  out.elements.resize(n);
  out.pulleys.resize(m.n_p());
  out.work.resize(n);
  out.contact.resize(n);
  const double* v = y + m.n_coord();
  sde_axial_forces(m, y, v, out.work.data());
  fill_contacts(m, d, t, y, out.contacts);
  const ContactView pairs = out.contacts.pairs();
  PairSums sums(out.contact, 0);
  for (const ContactPair& c : pairs) sums.add(c);
  double vb = 0;
  for (int i = 0; i < n; ++i) {
    out.elements[i] = element_with(d, sense, t, y, i, out.contact[i], out.work[i], out.work[after(i, n)]);
    vb += axis(y[3 * i + 2]).dot(Vec2(v[3 * i], v[3 * i + 1]));
  }
  out.belt_speed = vb / m.n_el();
  for (int j = 0; j < m.n_p(); ++j) out.pulleys[j] = pulley_with(m, d, t, y, j, pairs);
  classify_contact(m, out);
  wrap_speeds(m, sense, out);
}

void classify_contact(const Model& m, Observation& o) {
  const int n = static_cast<int>(o.elements.size());
  std::vector<ElementObs>& e = o.elements;
  for (ElementObs& x : e)
    if (x.state != ContactState::free) x.state = ContactState::stick;
  // k on the same contact arc as element `on` (same pulley, in contact)
  auto on_arc = [&](int k, int on) { return e[k].state != ContactState::free && e[k].pulley == e[on].pulley; };
  auto saturated = [&](int k) { return std::abs(e[k].slip) > m.friction_of(k).dv; };
  // the belt moves along the element numbers, or against them when the drive runs backwards
  const int dir = o.belt_speed < 0 ? -1 : 1;
  auto prev = [n, dir](int k) { return (k + n - dir) % n; };
  for (int x = 0; x < n; ++x) {
    // x is an exit: the last element of a contact arc in the direction the belt moves
    if (e[x].state == ContactState::free || on_arc((x + n + dir) % n, x)) continue;
    // the lift-off zone (observables.hpp): the elements that may lie past the tangent point,
    // sqrt(2·R·p̄) of span (p̄ the arc's mean penetration), at least the last one
    double depth = 0;
    int on = 0;
    for (int a = x; on < n && on_arc(a, x); a = prev(a)) depth += e[a].penetration, ++on;
    const int lift = std::max(
        1, static_cast<int>(std::ceil(std::sqrt(2 * m.pulleys[e[x].pulley].radius * depth / on) / m.belt.pitch)));
    int k = x;
    if (!saturated(k) && on_arc(prev(k), x)) k = prev(k);  // the last element lifting off inside the band
    // a backward run at the exit no longer than the zone, which stops there (not even across a
    // dip), is the belt lifting off and starts no run
    auto backward = [&](int a) { return saturated(a) && e[a].slip < 0; };
    int b = k, run = 0;  // b: the first element behind the backward run
    while (run <= lift && on_arc(b, x) && backward(b)) ++run, b = prev(b);
    if (run >= 1 && run <= lift && on_arc(b, x) && !(!saturated(b) && on_arc(prev(b), x) && backward(prev(b)))) {
      k = b;
      if (!saturated(k) && on_arc(prev(k), x)) k = prev(k);  // lifting off inside the band behind it
    }
    // the run of saturated elements in one direction from a (backwards along the belt), one
    // element dipping through the band inside it included: its length, and with mark its states
    auto saturated_run = [&](int a, bool mark) {
      const bool forward = e[a].slip > 0;
      auto with = [&](int i) { return saturated(i) && (e[i].slip > 0) == forward; };
      int len = 0;
      for (int count = 0; count < n && on_arc(a, x); ++count, a = prev(a), ++len) {
        if (!with(a) && !(!saturated(a) && on_arc(prev(a), x) && with(prev(a)))) break;
        if (mark) e[a].state = ContactState::slip;
      }
      return len;
    };
    const bool gross = saturated(k), gross_forward = e[k].slip > 0;
    if (gross) saturated_run(k, true);  // the gross-slip arc
    // elsewhere on the arc (its entry, its middle) a run longer than the entry's settling, in the
    // gross-slip arc's direction when there is one, is a slip zone of its own: a wet stretch or a
    // torque pulse arriving slips where it lands. A run the other way is the entry's tension
    // overshoot settling back.
    const int settle = std::max(kSettlingElements, lift);
    for (int a = x, count = 0; count < n && on_arc(a, x); ++count) {
      if (e[a].state == ContactState::slip || !saturated(a) || (gross && (e[a].slip > 0) != gross_forward)) {
        a = prev(a);
        continue;
      }
      const int len = saturated_run(a, false);
      if (len > settle) saturated_run(a, true);
      for (int i = 0; i < len; ++i) a = prev(a);
      count += len - 1;
    }
  }
  for (PulleyObs& p : o.pulleys) p.contact_arc = p.slip_arc = p.stick_arc = p.mu = 0;
  const double l = m.belt.pitch;
  for (const ElementObs& x : e) {
    if (x.state == ContactState::free) continue;
    PulleyObs& p = o.pulleys[x.pulley];
    p.contact_arc += l;
    p.mu += x.mu * l;
    (x.state == ContactState::slip ? p.slip_arc : p.stick_arc) += l;
  }
  for (PulleyObs& p : o.pulleys)
    p.mu = p.contact_arc > 0 ? p.mu / p.contact_arc : std::numeric_limits<double>::quiet_NaN();
}

void wrap_speeds(const Model& m, const std::vector<int>& sense, Observation& o) {
  const std::vector<ElementObs>& e = o.elements;
  const int n = static_cast<int>(e.size());
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  auto rides = [&](int i, int j) { return e[i].state != ContactState::free && e[i].pulley == j; };
  for (int j = 0; j < static_cast<int>(o.pulleys.size()); ++j) {
    // the slip summed over the gross-slip arc; the penetrations of all [0] and of the inner [1]
    // elements riding pulley j (both neighbours ride it too)
    double slip = 0, depth[2] = {0, 0};
    int count[2] = {0, 0};
    for (int i = 0; i < n; ++i) {
      if (!rides(i, j)) continue;
      if (e[i].state == ContactState::slip) slip += e[i].slip;
      const int inner = rides((i + n - 1) % n, j) && rides((i + 1) % n, j);
      for (int k = 0; k <= inner; ++k) depth[k] += e[i].penetration, ++count[k];
    }
    PulleyObs& p = o.pulleys[j];
    if (count[0] == 0) {
      p.belt_speed = p.slip_speed = p.slip_pitch = p.creep = p.creep_pitch = kNaN;
      continue;
    }
    const int k = count[1] > 0 ? 1 : 0;
    const double radius = m.pulleys[j].radius;
    const double v_rim = sense[j] * p.omega * radius;
    const double v_pitch = sense[j] * p.omega * (radius - depth[k] / count[k]);
    p.slip_pitch = slip / count[0];
    p.belt_speed = v_pitch + p.slip_pitch;
    p.slip_speed = p.belt_speed - v_rim;
    const bool moving = std::abs(p.belt_speed) > m.friction.dv;
    p.creep = moving ? 1 - v_rim / p.belt_speed : kNaN;
    p.creep_pitch = moving ? 1 - v_pitch / p.belt_speed : kNaN;
  }
}

void blend_contact(const Model& m, const Drive& d, const std::vector<int>& sense, double theta, const Observation& a,
                   const Observation& b, Observation& at) {
  auto mix = [theta](double u, double v) { return (1 - theta) * u + theta * v; };
  for (size_t i = 0; i < at.elements.size(); ++i) {
    const ElementObs &ea = a.elements[i], &eb = b.elements[i];
    ElementObs& e = at.elements[i];
    // contact made or lost inside the step: what the interpolated state gives
    if (ea.pulley != eb.pulley || ea.state == ContactState::free || eb.state == ContactState::free) continue;
    e.pulley = ea.pulley;
    e.normal = mix(ea.normal, eb.normal);
    e.friction = mix(ea.friction, eb.friction);
    e.slip = mix(ea.slip, eb.slip);
    e.penetration = mix(ea.penetration, eb.penetration);
    e.state = ContactState::stick;
  }
  for (size_t j = 0; j < at.pulleys.size(); ++j) {
    const PulleyObs &pa = a.pulleys[j], &pb = b.pulleys[j];
    PulleyObs& p = at.pulleys[j];
    p.belt_torque = mix(pa.belt_torque, pb.belt_torque);
    p.hub = (1 - theta) * pa.hub + theta * pb.hub;
    p.hub_load = p.hub.norm();
    const int k = static_cast<int>(j);
    if (d.kinematic(k)) p.torque = m.pulleys[j].inertia * d.speed_rate(k, at.t) - p.belt_torque;
  }
  classify_contact(m, at);
  wrap_speeds(m, sense, at);
}

}  // namespace beltsim
