// Spray zones: the elements' discrete states (the law is at the top of spray.hpp).
#include "model/spray.hpp"

#include <cmath>

namespace beltsim {

int spray_zone_of(const Spray& s, const double* q, int i) {
  const Vec2 P(q[3 * i], q[3 * i + 1]);
  for (size_t z = 0; z < s.zones.size(); ++z) {
    const SprayZone& zn = s.zones[z];
    if (zn.on && (P - zn.centre).squaredNorm() < zn.radius * zn.radius) return static_cast<int>(z);
  }
  return -1;
}

bool spray_changed(const Spray& s, int n, const double* q) {
  for (int i = 0; i < n; ++i)
    if (spray_zone_of(s, q, i) != s.el[i].zone) return true;
  return false;
}

std::vector<int> spray_switch(Spray& s, double t) {
  std::vector<int> changed;
  for (size_t z = 0; z < s.zones.size(); ++z) {
    SprayZone& zn = s.zones[z];
    const bool on = zn.enabled && zn.from <= t && t < zn.to;
    if (on != zn.on) zn.on = on, changed.push_back(static_cast<int>(z));
  }
  return changed;
}

bool spray_update(Spray& s, int n, double t, const double* q, const double* v) {
  bool changed = false;
  for (int i = 0; i < n; ++i) {
    ElementSpray& e = s.el[i];
    const int z = spray_zone_of(s, q, i);
    if (z == e.zone) continue;
    changed = true;
    const bool was_wet = e.zone >= 0 || e.drying;
    if (z >= 0) {
      e.zone = z, e.drying = false, e.t_in = t;
    } else {
      // it leaves the spray with its zone's μ and dries from here
      const SprayZone& left = s.zones[e.zone];
      e.mu_wet = left.mu, e.t_wet = t;
      e.rate = std::hypot(v[3 * i], v[3 * i + 1]) / left.drying_length;
      e.zone = -1, e.drying = true;
    }
    if (!was_wet) s.n_wet++;
  }
  return changed;
}

bool spray_dry(Spray& s, double t) {
  bool any = false;
  for (ElementSpray& e : s.el)
    if (e.drying && e.t_dry() <= t) e.drying = false, s.n_wet--, any = true;
  return any;
}

}  // namespace beltsim
