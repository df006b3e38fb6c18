// The structs scene_fields.hpp lists in a checkpoint's text (io/checkpoint_text.hpp), each field on
// a line of its own under the struct's prefix ("arm." + "pivot" -> "arm.pivot 0.075 -0.14"), and
// compared with one another bit for bit. The scene's and the drive's readers and writers
// (scene_io.hpp) are made of these. get reads what the text holds; the checks that need the rest
// of the scene (a pulley's number, one value per element) are the caller's.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>

#include "io/checkpoint_text.hpp"
#include "model/drive.hpp"
#include "model/model.hpp"
#include "scene/route.hpp"
#include "scene/scene.hpp"

namespace beltsim::fields {

// put: the struct's fields under `pre`; get: the same back; difference: the key (pre + the field's)
// of the first field in which a and b differ (doubles bit for bit: -0 is not 0), "" when none;
// lines: how many lines put writes
#define BELTSIM_FIELD_IO(Type)                                                  \
  void put(CheckpointWriter& w, const std::string& pre, const Type& s);         \
  void get(CheckpointReader& r, const std::string& pre, Type& s);               \
  std::string difference(const std::string& pre, const Type& a, const Type& b); \
  size_t lines(const Type*);

BELTSIM_FIELD_IO(Pulley)
BELTSIM_FIELD_IO(Arm)
BELTSIM_FIELD_IO(Coupling)
BELTSIM_FIELD_IO(Belt)
BELTSIM_FIELD_IO(Contact)
BELTSIM_FIELD_IO(Friction)
BELTSIM_FIELD_IO(SprayZone)
BELTSIM_FIELD_IO(Route::Span)
BELTSIM_FIELD_IO(Route::Arc)
BELTSIM_FIELD_IO(SceneInput)
BELTSIM_FIELD_IO(ElementSite)
BELTSIM_FIELD_IO(Ramp)
BELTSIM_FIELD_IO(Sine)
BELTSIM_FIELD_IO(Harmonic)
BELTSIM_FIELD_IO(PulleyDrive)
#undef BELTSIM_FIELD_IO

// a law, its tables, ramps, sines and harmonics. A law held by Lua code cannot be written:
// std::runtime_error naming it. (The laws' own rules are validate_law's, validate.hpp.)
void put(CheckpointWriter& w, const std::string& pre, const TimeSpeedLaw& law);
void get(CheckpointReader& r, const std::string& pre, TimeSpeedLaw& law);
std::string difference(const std::string& pre, const TimeSpeedLaw& a, const TimeSpeedLaw& b);

// every element's spray record, one line per field holding a value per element; get reads n
// values of each (fewer: refused naming the line) and leaves Spray::n_wet to the caller
void put(CheckpointWriter& w, const std::string& pre, const std::vector<ElementSpray>& el);
void get(CheckpointReader& r, const std::string& pre, size_t n, std::vector<ElementSpray>& el);
std::string difference(const std::string& pre, const std::vector<ElementSpray>& a, const std::vector<ElementSpray>& b);

// the model's, the drive's and the scene's own fields (BELTSIM_MODEL_FIELDS, BELTSIM_DRIVE_FIELDS,
// BELTSIM_SCENE_FIELDS)
void put_own(CheckpointWriter& w, const Model& m);
void get_own(CheckpointReader& r, Model& m);
std::string difference_own(const Model& a, const Model& b);
void put_own(CheckpointWriter& w, const Drive& d);
void get_own(CheckpointReader& r, Drive& d);
std::string difference_own(const Drive& a, const Drive& b);
void put_own(CheckpointWriter& w, const Scene& sc);
void get_own(CheckpointReader& r, Scene& sc);
std::string difference_own(const Scene& a, const Scene& b);

// a list of structs under one key: its count line, then each struct's lines; get believes the
// count as far as the lines left hold that many structs, and at most `most`
template <class T>
void put_list(CheckpointWriter& w, const std::string& count_key, const std::string& pre, const std::vector<T>& v) {
  w.line(count_key, static_cast<long>(v.size()));
  for (const T& s : v) put(w, pre, s);
}
// (each: called with each struct's index and the struct as read, for the checks that need the rest
// of the scene; its refusals name the lines just read, CheckpointReader::line_of)
template <class T, class Each = std::nullptr_t>
void get_list(CheckpointReader& r, const std::string& count_key, const std::string& pre, std::vector<T>& v,
              size_t most = SIZE_MAX, Each each = nullptr) {
  r.open(count_key);
  const size_t n = r.group_count(lines(static_cast<const T*>(nullptr)), most);
  r.close();
  v.resize(n);
  for (size_t k = 0; k < n; ++k) {
    get(r, pre, v[k]);
    if constexpr (!std::is_same_v<Each, std::nullptr_t>) each(k, v[k]);
  }
}
template <class T>
std::string difference_list(const std::string& pre, const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return pre + " (count)";
  for (size_t k = 0; k < a.size(); ++k)
    if (std::string d = difference(pre, a[k], b[k]); !d.empty()) return d + " [" + std::to_string(k) + "]";
  return "";
}

// the same value, bit for bit
bool same_value(double a, double b);
bool same_value(const Vec2& a, const Vec2& b);
bool same_value(const std::vector<double>& a, const std::vector<double>& b);
bool same_value(const Eigen::VectorXd& a, const Eigen::VectorXd& b);
bool same_value(const std::map<std::string, double>& a, const std::map<std::string, double>& b);
bool same_value(const TimeSpeedLaw& a, const TimeSpeedLaw& b);
template <class T>
bool same_value(const T& a, const T& b) {
  return a == b;
}

}  // namespace beltsim::fields
