// The parameter tables of docs/lua-api.md (parameters_markdown, scene/parameters.hpp), with the
// belt presets' (scene/belt_presets.hpp), which take their units from the parameter table.
#include <charconv>
#include <cmath>

#include "io/number_text.hpp"
#include "scene/belt_presets.hpp"
#include "scene/parameters.hpp"

namespace beltsim {

namespace {

// a default as the docs show it: "3.0256e9", "1e-3", "0.026", "500"
std::string doc_number(double v) {
  if (v == 0 || (std::abs(v) >= 1e-2 && std::abs(v) < 1e5)) return number_text(v);
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  std::string s(buf, r.ptr);  // "3.0256e+09"
  const size_t e = s.find('e');
  std::string exp = s.substr(e + 1);
  const bool neg = exp[0] == '-';
  exp = exp.substr(1);
  while (exp.size() > 1 && exp[0] == '0') exp.erase(0, 1);
  return s.substr(0, e + 1) + (neg ? "-" : "") + exp;
}

// a rule as the docs show it
std::string_view doc_range(Rule r) {
  switch (r) {
    case Rule::positive: return "> 0";
    case Rule::non_negative: return "≥ 0";
    case Rule::exponent: return "≥ 1";
    case Rule::at_least_three: return "≥ 3";
    case Rule::friction_coefficient: return "0 … 10";
    case Rule::slip_band: return "> 0, ≤ 1";
    case Rule::pulley_radius:
      return "> 0, ≤ 5";
    case Rule::strain:
      return "> 0, < 0.5";
    case Rule::finite: return "finite";
    case Rule::none: break;
  }
  return "—";
}

}  // namespace

std::string parameters_markdown() {
  std::string md;
  for (const auto& [table, title] : {std::pair{"scene", "`beltsim.scene{...}`"}, std::pair{"pulley", "Pulley table"},
                                     std::pair{"pulley.tensioner", "A pulley's `tensioner` table"},
                                     std::pair{"pulley.coupling", "A pulley's `coupling` table"},
                                     std::pair{"belt", "Belt table"}, std::pair{"belt.sde", "`belt.sde` table"},
                                     std::pair{"contact", "Contact table"}, std::pair{"friction", "Friction table"},
                                     std::pair{"friction.segments", "A `friction.segments` entry's table"},
                                     std::pair{"spray", "A `spray` zone's table"}}) {
    md.append(md.empty() ? "" : "\n").append(title).append(":\n\n| key | unit | default | range | meaning |\n|---|---|---|---|---|\n");
    for (const Parameter* p : parameters_of(table)) {
      std::string fallback;
      if (p->fallback)
        fallback.append("`").append(doc_number(*p->fallback)).append("`");
      else
        fallback.append(p->fallback_text.empty() ? "—" : p->fallback_text);
      if (p->whose != Whose::none) fallback.append(" (").append(whose_text(p->whose)).append(")");
      md.append("| `").append(p->key).append("` | ").append(p->unit.empty() ? "—" : p->unit);
      md.append(" | ").append(fallback).append(" | ").append(doc_range(p->rule)).append(" | ").append(p->note);
      md.append(" |\n");
    }
  }
  md.append("\nBelt presets (`belt.preset`, or `belt = beltsim.belts[\"6PK\"]`; docs/belts.md gives the sources):\n\n");
  return md.append(belt_presets_markdown());
}

}  // namespace beltsim
