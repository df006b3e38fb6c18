#include "scene/scene_io.hpp"

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <ios>
#include <locale>
#include <map>
#include <stdexcept>

namespace beltsim {

namespace {

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("checkpoint: " + what); }

// ---- writing: each field on its own line, "key value..." -----------------------------------

// hex floats and decimal integers in the classic locale, whatever the caller's stream was set to
class Writer {
 public:
  explicit Writer(std::ostream& out)
      : out_(out), flags_(out.flags()), locale_(out.imbue(std::locale::classic())) {
    out_.flags(std::ios_base::fixed | std::ios_base::scientific);  // = std::hexfloat, decimal ints
    out_.width(0);
  }
  ~Writer() {
    out_.flags(flags_);
    out_.imbue(locale_);
  }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  std::ostream& key(const std::string& k) { return out_ << k; }
  void end() { out_ << '\n'; }
  void num(double x) { out_ << ' ' << x; }
  void str(const std::string& s) {
    out_ << " \"";
    for (char c : s) {
      if (c == '"' || c == '\\') out_ << '\\' << c;
      else if (c == '\n') out_ << "\\n";
      else out_ << c;
    }
    out_ << '"';
  }

  void line(const std::string& k, double x) { key(k), num(x), end(); }
  void line(const std::string& k, long i) { key(k) << ' ' << i, end(); }
  void line(const std::string& k, const Vec2& v) { key(k), num(v.x()), num(v.y()), end(); }
  void line(const std::string& k, const std::string& s) { key(k), str(s), end(); }
  void line(const std::string& k, const double* x, size_t n) {
    key(k) << ' ' << n;
    for (size_t i = 0; i < n; ++i) num(x[i]);
    end();
  }
  void line(const std::string& k, const std::vector<double>& v) { line(k, v.data(), v.size()); }
  void line(const std::string& k, const std::vector<int>& v) {
    key(k) << ' ' << v.size();
    for (int i : v) out_ << ' ' << i;
    end();
  }
  void line(const std::string& k, const std::vector<std::string>& v) {
    key(k) << ' ' << v.size();
    for (const auto& s : v) str(s);
    end();
  }
  void line(const std::string& k, const std::map<std::string, double>& m) {
    key(k) << ' ' << m.size();
    for (const auto& [s, x] : m) str(s), num(x);
    end();
  }

 private:
  std::ostream& out_;
  std::ios_base::fmtflags flags_;
  std::locale locale_;
};

// ---- reading: one line at a time; every field checks its keyword ---------------------------

class Reader {
 public:
  explicit Reader(std::istream& in) : in_(in) {}

  // the next line, which must open with `key`; the values follow through the methods below
  void open(const std::string& key) {
    key_ = key;
    for (;;) {
      if (!std::getline(in_, line_)) fail("expected '" + key + "', got the end of the input");
      // a last line without its newline was cut short
      if (in_.eof()) fail("expected '" + key + "', got a truncated line at the end of the input");
      pos_ = 0;
      skip_blanks();
      if (pos_ < line_.size() && line_[pos_] != '#') break;
    }
    const std::string got = token();
    if (got != key) fail("expected '" + key + "', got '" + got + "'");
  }
  // nothing but blanks or a comment may follow the values
  void close() {
    skip_blanks();
    if (pos_ < line_.size() && line_[pos_] != '#')
      fail("'" + key_ + "': unexpected '" + token() + "' after the values");
  }

  double num() {
    const std::string t = token();
    if (t.empty()) fail("'" + key_ + "': expected a number, got the end of the line");
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size()) fail("'" + key_ + "': expected a number, got '" + t + "'");
    return x;
  }
  long integer(long lo, long hi) {
    const std::string t = token();
    if (t.empty()) fail("'" + key_ + "': expected an integer, got the end of the line");
    char* end = nullptr;
    errno = 0;
    const long i = std::strtol(t.c_str(), &end, 10);
    if (end != t.c_str() + t.size() || errno != 0) fail("'" + key_ + "': expected an integer, got '" + t + "'");
    if (i < lo || i > hi)
      fail("'" + key_ + "': " + t + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return i;
  }
  int count() { return static_cast<int>(integer(0, INT_MAX)); }
  std::string str() {
    skip_blanks();
    if (pos_ >= line_.size() || line_[pos_] != '"') fail("'" + key_ + "': expected a quoted string");
    std::string s;
    for (++pos_; pos_ < line_.size(); ++pos_) {
      char c = line_[pos_];
      if (c == '"') {
        ++pos_;
        return s;
      }
      if (c == '\\' && ++pos_ < line_.size()) c = line_[pos_] == 'n' ? '\n' : line_[pos_];
      s += c;
    }
    fail("'" + key_ + "': unterminated string");
  }
  std::string word() { return token(); }

  // whole lines of one field
  double line_num(const std::string& k) { return open(k), end_with(num()); }
  long line_int(const std::string& k, long lo, long hi) { return open(k), end_with(integer(lo, hi)); }
  Vec2 line_vec2(const std::string& k) {
    open(k);
    const double x = num();
    return end_with(Vec2(x, num()));
  }
  std::string line_str(const std::string& k) { return open(k), end_with(str()); }
  std::vector<double> line_doubles(const std::string& k) {
    open(k);
    std::vector<double> v;  // grown as read: a corrupt count fails on the values, not on memory
    for (int i = 0, n = count(); i < n; ++i) v.push_back(num());
    return end_with(std::move(v));
  }
  std::vector<int> line_ints(const std::string& k) {
    open(k);
    std::vector<int> v;
    for (int i = 0, n = count(); i < n; ++i) v.push_back(static_cast<int>(integer(INT_MIN, INT_MAX)));
    return end_with(std::move(v));
  }
  std::vector<std::string> line_strs(const std::string& k) {
    open(k);
    std::vector<std::string> v;
    for (int i = 0, n = count(); i < n; ++i) v.push_back(str());
    return end_with(std::move(v));
  }
  std::map<std::string, double> line_map(const std::string& k) {
    open(k);
    std::map<std::string, double> m;
    for (int i = 0, n = count(); i < n; ++i) {
      std::string s = str();
      m[s] = num();
    }
    return end_with(std::move(m));
  }
  // "key <version>" opening an object
  void header(const std::string& k) {
    const long v = line_int(k, 0, INT_MAX);
    if (v != kCheckpointVersion)
      fail("'" + k + "' is in format " + std::to_string(v) + ", this build reads format " +
           std::to_string(kCheckpointVersion));
  }
  void footer(const std::string& k) {
    open("end");
    const std::string w = word();
    if (w != k) fail("expected 'end " + k + "', got 'end " + w + "'");
    close();
  }

 private:
  template <class T>
  T end_with(T value) {
    close();
    return value;
  }
  void skip_blanks() {
    while (pos_ < line_.size() && (line_[pos_] == ' ' || line_[pos_] == '\t' || line_[pos_] == '\r')) ++pos_;
  }
  std::string token() {
    skip_blanks();
    const size_t b = pos_;
    while (pos_ < line_.size() && line_[pos_] != ' ' && line_[pos_] != '\t' && line_[pos_] != '\r') ++pos_;
    return line_.substr(b, pos_ - b);
  }

  std::istream& in_;
  std::string line_, key_;
  size_t pos_ = 0;
};

// ---- the objects --------------------------------------------------------------------------

void put_law(Writer& w, const TimeSpeedLaw& law, const std::string& k) {
  if (law.fn)
    throw std::runtime_error("checkpoint: the " + k + " law " + law.fn->describe() +
                             " is Lua code, which a checkpoint cannot hold");
  w.line(k + ".constant", law.constant);
  w.line(k + ".per_speed", law.per_speed);
  w.line(k + ".t", law.t);
  w.line(k + ".value", law.value);
  w.line(k + ".omega", law.omega);
  w.line(k + ".omega_value", law.omega_value);
  // ramps (t0 t1 from to cosine), sines (mean amplitude frequency phase), harmonics (order
  // amplitude phase mean_speed): each a flat list of numbers
  std::vector<double> r, s, h;
  for (const Ramp& a : law.ramps) r.insert(r.end(), {a.t0, a.t1, a.from, a.to, a.cosine ? 1.0 : 0.0});
  for (const Sine& a : law.sines) s.insert(s.end(), {a.mean, a.amplitude, a.frequency, a.phase});
  for (const Harmonic& a : law.harmonics) h.insert(h.end(), {a.order, a.amplitude, a.phase, a.mean_speed});
  w.line(k + ".ramps", r);
  w.line(k + ".sines", s);
  w.line(k + ".harmonics", h);
}
TimeSpeedLaw get_law(Reader& r, const std::string& k) {
  TimeSpeedLaw law;
  law.constant = r.line_num(k + ".constant");
  law.per_speed = r.line_num(k + ".per_speed");
  law.t = r.line_doubles(k + ".t");
  law.value = r.line_doubles(k + ".value");
  law.omega = r.line_doubles(k + ".omega");
  law.omega_value = r.line_doubles(k + ".omega_value");
  auto groups = [&](const std::string& key, size_t n) {
    std::vector<double> v = r.line_doubles(key);
    if (v.size() % n != 0) fail("'" + key + "': a multiple of " + std::to_string(n) + " numbers expected");
    return v;
  };
  const std::vector<double> ra = groups(k + ".ramps", 5), si = groups(k + ".sines", 4), ha = groups(k + ".harmonics", 4);
  for (size_t i = 0; i < ra.size(); i += 5) law.ramps.push_back({ra[i], ra[i + 1], ra[i + 2], ra[i + 3], ra[i + 4] != 0});
  for (size_t i = 0; i < si.size(); i += 4) law.sines.push_back({si[i], si[i + 1], si[i + 2], si[i + 3]});
  for (size_t i = 0; i < ha.size(); i += 4) law.harmonics.push_back({ha[i], ha[i + 1], ha[i + 2], ha[i + 3]});
  return law;
}

void put_model(Writer& w, const Model& m) {
  w.line("model", long{kCheckpointVersion});
  w.line("pulleys", long{m.n_p()});
  for (const Pulley& p : m.pulleys) {
    w.line("pulley", p.name);
    w.line("pulley.centre", p.centre);
    w.line("pulley.radius", p.radius);
    w.line("pulley.inertia", p.inertia);
    w.key("pulley.wrap") << (p.wrap == WrapSide::back ? " back" : " inside"), w.end();
  }
  const Belt& b = m.belt;
  w.line("belt.n", long{b.n});
  w.line("belt.pitch", b.pitch);
  w.line("belt.rigid_length", b.rigid_length);
  w.line("belt.mass", b.mass);
  w.line("belt.rot_inertia", b.rot_inertia);
  w.line("belt.k", b.k);
  w.line("belt.c", b.c);
  w.line("belt.kt", b.kt);
  w.line("belt.ct", b.ct);
  w.line("belt.e_tra", b.e_tra);
  w.line("belt.e_tor", b.e_tor);
  w.line("contact.c1", m.contact.c1);
  w.line("contact.c2", m.contact.c2);
  w.line("contact.b", m.contact.b);
  w.line("contact.p_max", m.contact.p_max);
  w.line("friction.dv", m.friction.dv);
  w.line("gravity", m.gravity);
  w.line("track_energy", long{m.track_energy});
  w.key("end model"), w.end();
}

void put_drive(Writer& w, const Drive& d) {
  w.line("drive", long{kCheckpointVersion});
  w.line("pulleys", static_cast<long>(d.pulleys.size()));
  for (const PulleyDrive& p : d.pulleys) {
    w.line("pulley.kinematic", long{p.kinematic});
    put_law(w, p.torque, "torque");
    put_law(w, p.speed, "speed");
  }
  w.line("mu", d.mu);
  w.line("restart_time", d.restart_time);
  w.key("end drive"), w.end();
}
Drive get_drive(Reader& r) {
  r.header("drive");
  Drive d;
  for (long j = 0, np = r.line_int("pulleys", 0, INT_MAX); j < np; ++j) {
    PulleyDrive& p = d.pulleys.emplace_back();
    p.kinematic = r.line_int("pulley.kinematic", 0, 1) != 0;
    p.torque = get_law(r, "torque");
    p.speed = get_law(r, "speed");
  }
  d.mu = r.line_doubles("mu");
  d.restart_time = r.line_num("restart_time");
  r.footer("drive");
  return d;
}
Model get_model(Reader& r) {
  r.header("model");
  Model m;
  for (long j = 0, np = r.line_int("pulleys", 0, INT_MAX); j < np; ++j) {
    Pulley& p = m.pulleys.emplace_back();
    p.name = r.line_str("pulley");
    p.centre = r.line_vec2("pulley.centre");
    p.radius = r.line_num("pulley.radius");
    p.inertia = r.line_num("pulley.inertia");
    r.open("pulley.wrap");
    const std::string wrap = r.word();
    if (wrap != "inside" && wrap != "back") fail("'pulley.wrap': expected inside or back, got '" + wrap + "'");
    p.wrap = wrap == "back" ? WrapSide::back : WrapSide::inside;
    r.close();
  }
  Belt& b = m.belt;
  b.n = static_cast<int>(r.line_int("belt.n", 0, INT_MAX));
  b.pitch = r.line_num("belt.pitch");
  b.rigid_length = r.line_num("belt.rigid_length");
  b.mass = r.line_num("belt.mass");
  b.rot_inertia = r.line_num("belt.rot_inertia");
  b.k = r.line_num("belt.k");
  b.c = r.line_num("belt.c");
  b.kt = r.line_num("belt.kt");
  b.ct = r.line_num("belt.ct");
  b.e_tra = r.line_num("belt.e_tra");
  b.e_tor = r.line_num("belt.e_tor");
  m.contact.c1 = r.line_num("contact.c1");
  m.contact.c2 = r.line_num("contact.c2");
  m.contact.b = r.line_num("contact.b");
  m.contact.p_max = r.line_num("contact.p_max");
  m.friction.dv = r.line_num("friction.dv");
  m.gravity = r.line_num("gravity");
  m.track_energy = r.line_int("track_energy", 0, 1) != 0;
  r.footer("model");
  return m;
}

void put_route(Writer& w, const Route& route) {
  w.line("route.spans", static_cast<long>(route.spans.size()));
  for (const Route::Span& s : route.spans) {
    w.line("span.from", s.from);
    w.line("span.to", s.to);
    w.line("span.length", s.length);
  }
  w.line("route.arcs", static_cast<long>(route.arcs.size()));
  for (const Route::Arc& a : route.arcs) {
    w.line("arc.centre", a.centre);
    w.line("arc.radius", a.radius);
    w.line("arc.sense", long{a.sense});
    w.line("arc.start_angle", a.start_angle);
    w.line("arc.angle", a.angle);
  }
  w.line("route.length", route.length);
}
Route get_route(Reader& r) {
  Route route;
  for (long k = 0, n = r.line_int("route.spans", 0, INT_MAX); k < n; ++k) {
    Route::Span& s = route.spans.emplace_back();
    s.from = r.line_vec2("span.from");
    s.to = r.line_vec2("span.to");
    s.length = r.line_num("span.length");
  }
  for (long k = 0, n = r.line_int("route.arcs", 0, INT_MAX); k < n; ++k) {
    Route::Arc& a = route.arcs.emplace_back();
    a.centre = r.line_vec2("arc.centre");
    a.radius = r.line_num("arc.radius");
    a.sense = static_cast<int>(r.line_int("arc.sense", INT_MIN, INT_MAX));
    a.start_angle = r.line_num("arc.start_angle");
    a.angle = r.line_num("arc.angle");
  }
  route.length = r.line_num("route.length");
  return route;
}

}  // namespace

void write_scene(std::ostream& out, const Scene& sc) {
  Writer w(out);
  w.line("scene", long{kCheckpointVersion});
  put_model(w, sc.model);
  put_drive(w, sc.drive);
  w.line("y0", sc.y0.data(), static_cast<size_t>(sc.y0.size()));
  put_route(w, sc.route);
  w.line("route_names", sc.route_names);
  w.line("route_pulleys", sc.route_pulleys);
  w.line("penetration", sc.penetration);
  w.key("reading") << (sc.reading == StiffnessReading::per_sde ? " per_sde" : " rigidity"), w.end();
  w.line("inputs", static_cast<long>(sc.inputs.size()));
  for (const SceneInput& e : sc.inputs) {
    w.line("input", e.name);
    w.line("input.value", e.value);
    w.line("input.text", e.text);
    w.line("input.unit", e.unit);
    w.line("input.given", long{e.given});
    w.line("input.note", e.note);
  }
  w.line("static_tension", sc.static_tension);
  w.line("static_residual", sc.static_residual);
  w.line("static_retried", long{sc.static_retried});
  w.line("span_sde", sc.span_sde);
  w.line("sites", static_cast<long>(sc.sites.size()));
  for (const ElementSite& e : sc.sites) {
    w.line("site", long{e.index});
    w.line("site.centre", e.centre);
    w.line("site.s", e.s);
    w.line("site.length", e.length);
    w.line("site.pulley", e.pulley);
    w.line("site.meets", e.meets);
    w.line("site.leaves", e.leaves);
  }
  w.key("end scene"), w.end();
}

Scene read_scene(std::istream& in) {
  Reader r(in);
  r.header("scene");
  Scene sc;
  sc.model = get_model(r);
  sc.drive = get_drive(r);
  const std::vector<double> y0 = r.line_doubles("y0");
  sc.y0 = Eigen::Map<const Eigen::VectorXd>(y0.data(), static_cast<Eigen::Index>(y0.size()));
  sc.route = get_route(r);
  sc.route_names = r.line_strs("route_names");
  sc.route_pulleys = r.line_ints("route_pulleys");
  sc.penetration = r.line_doubles("penetration");
  r.open("reading");
  const std::string reading = r.word();
  if (reading != "rigidity" && reading != "per_sde")
    fail("'reading': expected rigidity or per_sde, got '" + reading + "'");
  sc.reading = reading == "per_sde" ? StiffnessReading::per_sde : StiffnessReading::rigidity;
  r.close();
  for (long i = 0, n = r.line_int("inputs", 0, INT_MAX); i < n; ++i) {
    SceneInput& e = sc.inputs.emplace_back();
    e.name = r.line_str("input");
    e.value = r.line_num("input.value");
    e.text = r.line_str("input.text");
    e.unit = r.line_str("input.unit");
    e.given = r.line_int("input.given", 0, 1) != 0;
    e.note = r.line_str("input.note");
  }
  sc.static_tension = r.line_num("static_tension");
  sc.static_residual = r.line_num("static_residual");
  sc.static_retried = r.line_int("static_retried", 0, 1) != 0;
  sc.span_sde = r.line_ints("span_sde");
  for (long i = 0, n = r.line_int("sites", 0, INT_MAX); i < n; ++i) {
    ElementSite& e = sc.sites.emplace_back();
    e.index = static_cast<int>(r.line_int("site", INT_MIN, INT_MAX));
    e.centre = r.line_vec2("site.centre");
    e.s = r.line_num("site.s");
    e.length = r.line_num("site.length");
    e.pulley = r.line_str("site.pulley");
    e.meets = r.line_map("site.meets");
    e.leaves = r.line_map("site.leaves");
  }
  r.footer("scene");
  return sc;
}

void write_model(std::ostream& out, const Model& m) {
  Writer w(out);
  put_model(w, m);
}

Model read_model(std::istream& in) {
  Reader r(in);
  return get_model(r);
}

void write_drive(std::ostream& out, const Drive& d) {
  Writer w(out);
  put_drive(w, d);
}

Drive read_drive(std::istream& in) {
  Reader r(in);
  return get_drive(r);
}

void write_law(std::ostream& out, const TimeSpeedLaw& law, const std::string& key) {
  Writer w(out);
  put_law(w, law, key);
}

TimeSpeedLaw read_law(std::istream& in, const std::string& key) {
  Reader r(in);
  return get_law(r, key);
}

void write_vector(std::ostream& out, const Eigen::VectorXd& v, const std::string& key) {
  Writer w(out);
  w.line(key, v.data(), static_cast<size_t>(v.size()));
}

Eigen::VectorXd read_vector(std::istream& in, const std::string& key) {
  Reader r(in);
  const std::vector<double> v = r.line_doubles(key);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

void write_vector(std::ostream& out, const std::vector<double>& v, const std::string& key) {
  Writer w(out);
  w.line(key, v);
}

std::vector<double> read_std_vector(std::istream& in, const std::string& key) {
  Reader r(in);
  return r.line_doubles(key);
}

}  // namespace beltsim
