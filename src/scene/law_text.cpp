#include "scene/law_text.hpp"

#include <string_view>

#include "io/number_text.hpp"

namespace beltsim {

namespace {

// the text of a law, its numbers as number_text writes them (each reads back as the same double)
struct LawText {
  std::string s;
  LawText& operator<<(double v) {
    append_number(s, v);
    return *this;
  }
  LawText& operator<<(std::string_view t) {
    s += t;
    return *this;
  }
};

}  // namespace

std::string law_text(const TimeSpeedLaw& law) {
  LawText s;
  const bool plain = law.per_speed == 0 && law.t.empty() && law.omega.empty() && law.ramps.empty() &&
                     law.sines.empty() && law.harmonics.empty() && !law.fn;
  if (plain) {
    s << law.constant;
    return s.s;
  }
  s << "{ constant = " << law.constant;
  if (law.per_speed != 0) s << ", per_speed = " << law.per_speed;
  auto pairs = [&](const char* key, const std::vector<double>& x, const std::vector<double>& y) {
    if (x.empty()) return;
    s << ", " << key << " = {";
    for (size_t k = 0; k < x.size(); ++k) s << (k ? ", " : " ") << "{" << x[k] << ", " << y[k] << "}";
    s << " }";
  };
  pairs("table", law.t, law.value);
  pairs("per_speed_table", law.omega, law.omega_value);
  for (const Ramp& r : law.ramps) {
    if (r.is_step())
      s << ", { step = { t = " << r.t0 << ", from = " << r.from << ", to = " << r.to << " } }";
    else
      s << ", { ramp = { t0 = " << r.t0 << ", t1 = " << r.t1 << ", from = " << r.from << ", to = " << r.to
        << ", shape = \"" << (r.cosine ? "cosine" : "linear") << "\" } }";
  }
  for (const Sine& x : law.sines)
    s << ", { sine = { mean = " << x.mean << ", amplitude = " << x.amplitude << ", frequency = " << x.frequency
      << ", phase = " << x.phase << " } }";
  for (size_t k = 0; k < law.harmonics.size(); ++k) {
    const Harmonic& h = law.harmonics[k];
    if (k == 0 || h.mean_speed != law.harmonics[k - 1].mean_speed)
      s << (k ? " } }" : "") << ", { mean_speed = " << h.mean_speed << ", harmonics = {";
    else
      s << ",";
    s << " {" << h.order << ", " << h.amplitude << ", " << h.phase << "}";
    if (k + 1 == law.harmonics.size()) s << " } }";
  }
  if (law.fn) s << ", " << law.fn->describe();
  s << " }";
  return s.s;
}

}  // namespace beltsim
