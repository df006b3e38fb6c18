// The Scene's lookups and the span tensions (scene/scene_types.hpp).
#include "scene/scene_types.hpp"

#include "model/forces.hpp"

namespace beltsim {

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
  // the span the belt runs along from a to b; else the one from b to a (two pulleys have both)
  const size_t n = route_names.size();
  for (int pass = 0; pass < 2; ++pass)
    for (size_t k = 0; k < n; ++k) {
      const std::string& from = route_names[k];
      const std::string& to = route_names[(k + 1) % n];
      if (pass == 0 ? (from == a && to == b) : (from == b && to == a)) return static_cast<int>(k);
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

int span_sde(const Model& m, const Route::Span& sp, const double* y) {
  return sde_nearest(m, y, 0.5 * (sp.from + sp.to));
}

double span_force(const Model& m, const Route::Span& sp, const double* y) {
  return sde_axial_force(m, y, y + m.n_coord(), span_sde(m, sp, y));
}

}  // namespace beltsim
