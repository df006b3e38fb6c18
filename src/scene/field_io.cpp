#include "scene/field_io.hpp"

#include <climits>
#include <cstring>
#include <stdexcept>

#include "scene/scene_fields.hpp"

namespace beltsim::fields {

namespace {

// ---- each kind of field (scene_fields.hpp) -----------------------------------------------------

using W = CheckpointWriter;
using R = CheckpointReader;
using K = std::string;

void put_real(W& w, const K& k, double x) {
  w.line(k, x);
}
void put_real_inf(W& w, const K& k, double x) {
  w.line(k, x);
}
void put_integer(W& w, const K& k, int i) {
  w.line(k, i);
}
void put_sign(W& w, const K& k, int i) {
  w.line(k, i);
}
void put_flag(W& w, const K& k, bool b) {
  w.line(k, b);
}
void put_text(W& w, const K& k, const std::string& s) {
  w.line(k, s);
}
void put_point(W& w, const K& k, const Vec2& p) {
  w.fixed(k, {p.x(), p.y()});
}
void put_places(W& w, const K& k, const std::map<std::string, double>& m) {
  w.line(k, m);
}
void put_reals(W& w, const K& k, const std::vector<double>& v) {
  w.line(k, v);
}
void put_integers(W& w, const K& k, const std::vector<int>& v) {
  w.line(k, v);
}
void put_texts(W& w, const K& k, const std::vector<std::string>& v) {
  w.line(k, v);
}
void put_wrap(W& w, const K& k, WrapSide s) {
  w.word(k, s == WrapSide::back ? "back" : "inside");
}
void put_law(W& w, const K& k, FrictionKind f) {
  w.word(k, friction_law_name(f));
}
void put_timelaw(W& w, const K& k, const TimeSpeedLaw& law) {
  put(w, k, law);
}
void put_reading(W& w, const K& k, StiffnessReading s) {
  w.word(k, s == StiffnessReading::per_sde ? "per_sde" : "rigidity");
}

void get_real(R& r, const K& k, double& x) {
  x = r.line_num(k);
}
void get_real_inf(R& r, const K& k, double& x) {
  r.open(k);
  x = r.num_or_infinity();
  r.close();
}
void get_integer(R& r, const K& k, int& i) {
  i = static_cast<int>(r.line_int(k, INT_MIN, INT_MAX));
}
void get_sign(R& r, const K& k, int& i) {
  i = static_cast<int>(r.line_int(k, -1, 1));
}
void get_flag(R& r, const K& k, bool& b) {
  b = r.line_bool(k);
}
void get_text(R& r, const K& k, std::string& s) {
  s = r.line_str(k);
}
void get_point(R& r, const K& k, Vec2& p) {
  const std::vector<double> v = r.line_fixed(k, 2);
  p = Vec2(v[0], v[1]);
}
void get_places(R& r, const K& k, std::map<std::string, double>& m) {
  m = r.line_map(k);
}
void get_reals(R& r, const K& k, std::vector<double>& v) {
  v = r.line_doubles(k);
}
void get_integers(R& r, const K& k, std::vector<int>& v) {
  v = r.line_ints(k, INT_MIN, INT_MAX);
}
void get_texts(R& r, const K& k, std::vector<std::string>& v) {
  v = r.line_strs(k);
}
void get_wrap(R& r, const K& k, WrapSide& s) {
  s = r.line_choice(k, {"inside", "back"}) == 1 ? WrapSide::back : WrapSide::inside;
}
void get_law(R& r, const K& k, FrictionKind& f) {
  f = static_cast<FrictionKind>(r.line_choice(k, {"threlfall", "stribeck", "lugre"}));  // FrictionKind's order
}
void get_timelaw(R& r, const K& k, TimeSpeedLaw& law) {
  get(r, k, law);
}
void get_reading(R& r, const K& k, StiffnessReading& s) {
  s = r.line_choice(k, {"rigidity", "per_sde"}) == 1 ? StiffnessReading::per_sde : StiffnessReading::rigidity;
}

// the lists' expansions: s is the struct written or read, a and b the two compared
#define BELTSIM_PUT(kind, member, key, unit) put_##kind(w, pre + key, s.member);
#define BELTSIM_GET(kind, member, key, unit) get_##kind(r, pre + key, s.member);
#define BELTSIM_DIFF(kind, member, key, unit) \
  if (!same_value(a.member, b.member)) return pre + key;
#define BELTSIM_ONE(kind, member, key, unit) +1

#define BELTSIM_FIELD_IO(Type, LIST)                                                            \
  void put(W& w, const K& pre, const Type& s) {                                                 \
    LIST(BELTSIM_PUT, BELTSIM_PUT)                                                              \
  }                                                                                             \
  void get(R& r, const K& pre, Type& s){LIST(BELTSIM_GET, BELTSIM_GET)} std::string difference( \
      const K& pre, const Type& a, const Type& b) {                                             \
    LIST(BELTSIM_DIFF, BELTSIM_DIFF)                                                            \
    return "";                                                                                  \
  }                                                                                             \
  size_t lines(const Type*) {                                                                   \
    return 0 LIST(BELTSIM_ONE, BELTSIM_ONE);                                                    \
  }

}  // namespace

BELTSIM_FIELD_IO(Ramp, BELTSIM_RAMP_FIELDS)
BELTSIM_FIELD_IO(Sine, BELTSIM_SINE_FIELDS)
BELTSIM_FIELD_IO(Harmonic, BELTSIM_HARMONIC_FIELDS)
BELTSIM_FIELD_IO(Pulley, BELTSIM_PULLEY_FIELDS)
BELTSIM_FIELD_IO(Arm, BELTSIM_ARM_FIELDS)
BELTSIM_FIELD_IO(Coupling, BELTSIM_COUPLING_FIELDS)
BELTSIM_FIELD_IO(Belt, BELTSIM_BELT_FIELDS)
BELTSIM_FIELD_IO(Contact, BELTSIM_CONTACT_FIELDS)
BELTSIM_FIELD_IO(Friction, BELTSIM_FRICTION_FIELDS)
BELTSIM_FIELD_IO(SprayZone, BELTSIM_SPRAY_ZONE_FIELDS)
BELTSIM_FIELD_IO(Route::Span, BELTSIM_SPAN_FIELDS)
BELTSIM_FIELD_IO(Route::Arc, BELTSIM_ARC_FIELDS)
BELTSIM_FIELD_IO(SceneInput, BELTSIM_INPUT_FIELDS)
BELTSIM_FIELD_IO(ElementSite, BELTSIM_SITE_FIELDS)
BELTSIM_FIELD_IO(PulleyDrive, BELTSIM_PULLEY_DRIVE_FIELDS)

// ---- laws: "pulley.torque.constant 2", "pulley.torque.ramp.t0 0", ... --------------------------

void put(W& w, const K& law, const TimeSpeedLaw& s) {
  if (s.fn)
    throw std::runtime_error("checkpoint: the " + law + " law " + s.fn->describe() +
                             " is Lua code, which a checkpoint cannot hold");
  const K pre = law + ".";
  BELTSIM_LAW_FIELDS(BELTSIM_PUT, BELTSIM_PUT)
  put_list(w, pre + "ramps", pre + "ramp.", s.ramps);
  put_list(w, pre + "sines", pre + "sine.", s.sines);
  put_list(w, pre + "harmonics", pre + "harmonic.", s.harmonics);
}

void get(R& r, const K& law, TimeSpeedLaw& s) {
  s = TimeSpeedLaw();
  const K pre = law + ".";
  BELTSIM_LAW_FIELDS(BELTSIM_GET, BELTSIM_GET)
  get_list(r, pre + "ramps", pre + "ramp.", s.ramps);
  get_list(r, pre + "sines", pre + "sine.", s.sines);
  get_list(r, pre + "harmonics", pre + "harmonic.", s.harmonics);
}

std::string difference(const K& law, const TimeSpeedLaw& a, const TimeSpeedLaw& b) {
  const K pre = law + ".";
  BELTSIM_LAW_FIELDS(BELTSIM_DIFF, BELTSIM_DIFF)
  if (a.fn != b.fn) return law + " (its Lua code)";
  for (const std::string& d :
       {difference_list(pre + "ramp.", a.ramps, b.ramps), difference_list(pre + "sine.", a.sines, b.sines),
        difference_list(pre + "harmonic.", a.harmonics, b.harmonics)})
    if (!d.empty()) return d;
  return "";
}

// ---- the elements' spray records: a column per field -------------------------------------------

namespace {

template <class T>
std::vector<T> column(const std::vector<ElementSpray>& el, T ElementSpray::*m) {
  std::vector<T> c;
  for (const ElementSpray& e : el) c.push_back(e.*m);
  return c;
}
void put_column_integer(W& w, const K& k, const std::vector<ElementSpray>& el, int ElementSpray::*m) {
  w.line(k, column(el, m));
}
void put_column_flag(W& w, const K& k, const std::vector<ElementSpray>& el, bool ElementSpray::*m) {
  std::vector<int> c;
  for (const ElementSpray& e : el) c.push_back(e.*m ? 1 : 0);
  w.line(k, c);
}
void put_column_real(W& w, const K& k, const std::vector<ElementSpray>& el, double ElementSpray::*m) {
  w.line(k, column(el, m));
}

void one_each(R& r, size_t got, size_t n) {
  if (got != n) r.fail(std::to_string(got) + " values for " + std::to_string(n) + " elements");
}
void get_column_integer(R& r, const K& k, size_t n, std::vector<ElementSpray>& el, int ElementSpray::*m) {
  const std::vector<int> c = r.line_ints(k, INT_MIN, INT_MAX, n);
  one_each(r, c.size(), n);
  for (size_t i = 0; i < n; ++i) el[i].*m = c[i];
}
void get_column_flag(R& r, const K& k, size_t n, std::vector<ElementSpray>& el, bool ElementSpray::*m) {
  const std::vector<int> c = r.line_ints(k, 0, 1, n);
  one_each(r, c.size(), n);
  for (size_t i = 0; i < n; ++i) el[i].*m = c[i] == 1;
}
void get_column_real(R& r, const K& k, size_t n, std::vector<ElementSpray>& el, double ElementSpray::*m) {
  const std::vector<double> c = r.line_doubles(k, n);
  one_each(r, c.size(), n);
  for (size_t i = 0; i < n; ++i) el[i].*m = c[i];
}

}  // namespace

#define BELTSIM_PUT_COLUMN(kind, member, key, unit) put_column_##kind(w, pre + key, el, &ElementSpray::member);
#define BELTSIM_GET_COLUMN(kind, member, key, unit) get_column_##kind(r, pre + key, n, el, &ElementSpray::member);

void put(W& w, const K& pre, const std::vector<ElementSpray>& el) {
  BELTSIM_ELEMENT_SPRAY_FIELDS(BELTSIM_PUT_COLUMN, BELTSIM_PUT_COLUMN)
}

void get(R& r, const K& pre, size_t n, std::vector<ElementSpray>& el) {
  el.assign(n, ElementSpray());
  BELTSIM_ELEMENT_SPRAY_FIELDS(BELTSIM_GET_COLUMN, BELTSIM_GET_COLUMN)
}

std::string difference(const K& pre, const std::vector<ElementSpray>& ea, const std::vector<ElementSpray>& eb) {
  if (ea.size() != eb.size()) return pre + " (count)";
  for (size_t i = 0; i < ea.size(); ++i) {
    const ElementSpray &a = ea[i], &b = eb[i];
    BELTSIM_ELEMENT_SPRAY_FIELDS(BELTSIM_DIFF, BELTSIM_DIFF)
  }
  return "";
}

// ---- the model's and the scene's own fields ---------------------------------------------------

void put_own(W& w, const Model& s) {
  const K pre;
  BELTSIM_MODEL_FIELDS(BELTSIM_PUT, BELTSIM_PUT)
}
void get_own(R& r, Model& s) {
  const K pre;
  BELTSIM_MODEL_FIELDS(BELTSIM_GET, BELTSIM_GET)
}
std::string difference_own(const Model& a, const Model& b) {
  const K pre;
  BELTSIM_MODEL_FIELDS(BELTSIM_DIFF, BELTSIM_DIFF)
  return "";
}
void put_own(W& w, const Drive& s) {
  const K pre;
  BELTSIM_DRIVE_FIELDS(BELTSIM_PUT, BELTSIM_PUT)
}
void get_own(R& r, Drive& s) {
  const K pre;
  BELTSIM_DRIVE_FIELDS(BELTSIM_GET, BELTSIM_GET)
}
std::string difference_own(const Drive& a, const Drive& b) {
  const K pre;
  BELTSIM_DRIVE_FIELDS(BELTSIM_DIFF, BELTSIM_DIFF)
  return "";
}
void put_own(W& w, const Scene& s) {
  const K pre;
  BELTSIM_SCENE_FIELDS(BELTSIM_PUT, BELTSIM_PUT)
}
void get_own(R& r, Scene& s) {
  const K pre;
  BELTSIM_SCENE_FIELDS(BELTSIM_GET, BELTSIM_GET)
}
std::string difference_own(const Scene& a, const Scene& b) {
  const K pre;
  BELTSIM_SCENE_FIELDS(BELTSIM_DIFF, BELTSIM_DIFF)
  return "";
}

// ---- the same value, bit for bit ---------------------------------------------------------------

bool same_value(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same_value(const Vec2& a, const Vec2& b) {
  return same_value(a.x(), b.x()) && same_value(a.y(), b.y());
}
bool same_value(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}
bool same_value(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), static_cast<size_t>(a.size()) * sizeof(double)) == 0);
}
bool same_value(const TimeSpeedLaw& a, const TimeSpeedLaw& b) {
  return difference("", a, b).empty();
}
bool same_value(const std::map<std::string, double>& a, const std::map<std::string, double>& b) {
  if (a.size() != b.size()) return false;
  for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
    if (i->first != j->first || !same_value(i->second, j->second)) return false;
  return true;
}

}  // namespace beltsim::fields
