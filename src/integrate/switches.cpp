// Switching functions: where the contact and friction laws (model/contact_law.hpp) change their
// smooth piece, read from the laws themselves (normal_law, friction_law). For element i (centre
// P, velocity V) and pulley j (centre c, radius R, speed ω), with r = |P - c|, p = R - r,
// ṗ = -n·V, n = (P - c)/r, t = n rotated +90°:
//   contact onset      p = 0                  g0 = R - r
//   damping ramp end   p = p_max              g1 = p - p_max
//   clamp              N_el + δ(p)·b·ṗ = 0    g2 = (c1·p + c2)·p + min(p/p_max, 1)·b·ṗ  (p > 0)
//                                                  c2·p                                  (p <= 0)
//   friction band      |v_T| = Δv             g3 = |v_T| - Δv  (pushing; otherwise Δv; always Δv
//                                                               under LuGre's law, which has no band)
// with v_T = V·t - ω·r. g0, g1 and g2 are continuous in the state (at p = 0 both pieces of g2
// are 0). g3 jumps where the pair starts or stops pushing, which is a zero of g2 and so a kink
// already; outside contact the band has no force behind it and gives no kink. Every function is
// defined for every pair, in or out of contact, so that the count is fixed.
#include "integrate/switches.hpp"

#include <cmath>

#include "model/contact_law.hpp"

namespace beltsim {

int switch_count(const Model& m) { return kSwitchesPerPair * m.n_p() * m.belt.n; }

void contact_switches(const Model& m, const ContactView& pairs, double* g) {
  const Contact& c = m.contact;
  for (const ContactPair& pr : pairs) {
    const Friction& f = m.friction_of(pr.i);
    const double band = f.dv;
    const bool banded = f.law != FrictionKind::lugre;
    double* gi = g + kSwitchesPerPair * (pr.j * m.belt.n + pr.i);
    const NormalLaw& nl = pr.nl;
    gi[0] = nl.p;
    gi[1] = nl.p - c.p_max;
    if (pr.touching) {
      gi[2] = nl.N_free;
      gi[3] = nl.pushing && banded ? std::abs(pr.fl.vT) - band : band;
    } else {  // p <= 0
      gi[2] = c.c2 * nl.p;
      gi[3] = band;
    }
  }
}

}  // namespace beltsim
