#include "sim/state_io.hpp"

#include <climits>
#include <cmath>
#include <optional>

#include "io/number_text.hpp"
#include "scene/scene_io.hpp"

namespace beltsim {

namespace {

// ---- the schedule ---------------------------------------------------------------------------

void write_schedule(CheckpointWriter& w, const Timeline::State& s, const std::vector<MuEvent>& pending) {
  w.line("now", s.now);
  w.line("streams", s.next);
  std::vector<int> last;
  std::vector<double> crossing;
  for (const Timeline::WhenState& c : s.when) last.push_back(c.last ? 1 : 0), crossing.push_back(c.crossing);
  w.line("when.last", last);
  w.line("when.crossing", crossing);
  w.line("pending", static_cast<long>(pending.size()));
  for (const MuEvent& ev : pending) {
    w.line("event.t", ev.t);
    w.line("event.what", ev.what);
    w.line("event.text", ev.text);
    w.line("event.mu", ev.mu);
    w.line("event.share", ev.share);
  }
}

void read_schedule(CheckpointReader& r, size_t n, Timeline::State& s, std::vector<MuEvent>& pending) {
  s.now = r.line_num("now");
  if (!(s.now >= 0)) r.fail("a time >= 0 s expected");
  s.next = r.line_longs("streams", 0, LONG_MAX);
  const std::vector<int> last = r.line_ints("when.last", 0, 1);
  const std::vector<double> crossing = r.line_doubles_or_nan("when.crossing", last.size());
  if (crossing.size() != last.size())
    r.fail(std::to_string(crossing.size()) + " crossings for " + std::to_string(last.size()) + " conditions");
  for (size_t k = 0; k < last.size(); ++k) s.when.push_back({last[k] == 1, crossing[k]});
  r.open("pending");
  pending.resize(r.group_count(5));
  r.close();
  for (MuEvent& ev : pending) {
    ev.t = r.line_num("event.t");
    if (const std::string bad = event_time_problem(ev.t); !bad.empty()) r.fail("an event's time " + bad);
    if (!(ev.t >= s.now)) r.fail("an event still ahead must come at or after the checkpoint's time");
    ev.what = r.line_str("event.what");
    ev.text = r.line_str("event.text");
    ev.mu = r.line_doubles_or_nan("event.mu", n);
    if (ev.mu.size() != n) r.fail(std::to_string(ev.mu.size()) + " values for " + std::to_string(n) + " elements");
    for (double mu : ev.mu)
      if (!std::isnan(mu) && !(mu >= 0)) r.fail("μ must be >= 0 (got " + number_text(mu) + ")");
    ev.share = r.line_doubles("event.share", n);
    if (!ev.share.empty() && ev.share.size() != n)
      r.fail(std::to_string(ev.share.size()) + " shares for " + std::to_string(n) + " elements");
    for (double w : ev.share)
      if (!(w >= 0 && w <= 1)) r.fail("a share of the new μ must be in [0, 1] (got " + number_text(w) + ")");
  }
}

// ---- the outputs, the interval means, the callbacks' count and the wall time ----------------

void write_outputs(CheckpointWriter& w, const SimState& s) {
  const Outputs::State& o = s.outputs;
  w.line("rows", o.rows);
  w.line("frames_written", o.frames);
  // the outputs' sizes (0 for one that is not there)
  w.line("csv_bytes", o.csv_bytes);
  w.line("events_bytes", o.events_bytes);
  w.line("snapshots_bytes", o.snapshots_bytes);
  // what the files held (version 13): a resume refuses a folder another run has written since
  w.optional("csv_last_t", std::isnan(o.csv_last_t) ? std::nullopt : std::optional<double>(o.csv_last_t));
  w.hash("csv_fnv1a64", o.csv_hash);
  w.hash("events_fnv1a64", o.events_hash);
  w.hash("snapshots_fnv1a64", o.snapshots_hash);
  w.line("parameters_bytes", o.parameters_bytes);
  w.hash("parameters_fnv1a64", o.parameters_hash);
  w.line("mean_from", s.means.from);
  w.line("mean_covered", s.means.covered);
  w.line("mean_acc", s.means.integral);
  w.line("callbacks", s.callbacks);
  w.line("wall", s.wall);
}

void read_outputs(CheckpointReader& r, const Scene& sc, SimState& s) {
  Outputs::State& o = s.outputs;
  o.rows = r.line_int("rows", 0, LONG_MAX);
  o.frames = r.line_int("frames_written", 0, LONG_MAX);
  o.csv_bytes = r.line_int("csv_bytes", 0, LONG_MAX);
  o.events_bytes = r.line_int("events_bytes", 0, LONG_MAX);
  o.snapshots_bytes = r.line_int("snapshots_bytes", 0, LONG_MAX);
  if (r.version() >= 13) {
    const std::optional<double> t = r.line_optional("csv_last_t");
    if (t.has_value() != (o.rows > 0))
      r.fail(o.rows > 0 ? "the time of the last of " + std::to_string(o.rows) + " rows expected, got none"
                        : "no row written, so no last row's time (none expected)");
    if (t && !(*t >= 0)) r.fail("a time >= 0 s expected");
    o.csv_last_t = t.value_or(NAN);
    o.csv_hash = r.line_hash("csv_fnv1a64");
    o.events_hash = r.line_hash("events_fnv1a64");
    o.snapshots_hash = r.line_hash("snapshots_fnv1a64");
    o.parameters_bytes = r.line_int("parameters_bytes", 0, LONG_MAX);
    o.parameters_hash = r.line_hash("parameters_fnv1a64");
  } else {
    o.fingerprinted = false;  // (a resume takes them from the files, and says it could not check them)
  }
  IntervalMeans::State& m = s.means;
  m.from = r.line_num("mean_from");
  m.covered = r.line_num("mean_covered");
  if (!(m.from <= m.covered && m.covered <= s.now())) r.fail("the interval means must cover a time up to now");
  // pulley j's torque and belt torque, then each span's tension (interval_means.hpp)
  const size_t n_means = 2 * sc.model.pulleys.size() + sc.route.spans.size();
  m.integral = r.line_doubles("mean_acc", n_means);
  if (m.integral.size() != n_means)
    r.fail(std::to_string(m.integral.size()) + " integrals for the scene's " + std::to_string(n_means));
  s.callbacks = static_cast<int>(r.line_int("callbacks", 0, INT_MAX));
  s.wall = r.line_num("wall");
  if (!(s.wall >= 0)) r.fail("a wall time >= 0 s expected");
}

// ---- the integrator -------------------------------------------------------------------------

void write_integrator(CheckpointWriter& w, const IntegratorState& s) {
  w.line("integrator.state", s.method);
  w.line("integrator.t", s.t);
  w.line("integrator.t_prev", s.t_prev);
  w.line("integrator.h", s.h);
  w.line("integrator.h_used", s.h_used);
  w.line("integrator.h_cap", s.h_cap);
  w.line("integrator.started", s.started);
  w.line("integrator.worst", s.worst);
  w.line("integrator.at_floor", s.at_floor);
  w.line("integrator.failed_in_a_row", s.failed_in_a_row);
  auto vec = [&](const char* k, const Eigen::VectorXd& v) { w.line(k, v.data(), static_cast<size_t>(v.size())); };
  vec("integrator.y", s.y), vec("integrator.f", s.f), vec("integrator.y_prev", s.y_prev);
  vec("integrator.f_prev", s.f_prev);
  // the held step's interior states, one after the other
  w.line("integrator.interior_c", s.interior_c);
  std::vector<double> z;
  for (const Eigen::VectorXd& v : s.interior) z.insert(z.end(), v.data(), v.data() + v.size());
  w.line("integrator.interior", z);
  const WorkCounters& c = s.counters;
  w.line("integrator.counters",
         std::vector<long>{c.steps, c.rejected, c.rhs, c.jacobians, c.factorizations, c.solves, c.kink_restarts});
  // each kind of warning's count and first time (integrate/warnings.hpp: in WarningKind's order)
  std::vector<long> count;
  std::vector<double> first_t;
  for (const WarningStat& st : c.warnings.stat) count.push_back(st.count), first_t.push_back(st.first_t);
  w.line("integrator.warnings.count", count);
  w.line("integrator.warnings.first_t", first_t);
}

// `widen`: the file's states lack that many values at `at` (an older version's), read as zeros
void read_integrator(CheckpointReader& r, size_t n, IntegratorState& s, size_t at, size_t widen) {
  auto widened = [&](std::vector<double> x, size_t count) {
    if (widen == 0 || x.size() != count * (n - widen)) return x;
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i) {
      const auto from = x.begin() + static_cast<std::ptrdiff_t>(i * (n - widen));
      out.insert(out.end(), from, from + static_cast<std::ptrdiff_t>(at));
      out.insert(out.end(), widen, 0.0);
      out.insert(out.end(), from + static_cast<std::ptrdiff_t>(at), from + static_cast<std::ptrdiff_t>(n - widen));
    }
    return out;
  };
  s.method = r.line_str("integrator.state");
  s.t = r.line_num("integrator.t");
  s.t_prev = r.line_num("integrator.t_prev");
  s.h = r.line_num("integrator.h");
  s.h_used = r.line_num("integrator.h_used");
  r.open("integrator.h_cap");
  s.h_cap = r.num_or_infinity();
  r.close();
  s.started = r.line_bool("integrator.started");
  s.worst = static_cast<int>(r.line_int("integrator.worst", -1, static_cast<long>(n) - 1));
  s.at_floor = r.line_int("integrator.at_floor", 0, LONG_MAX);
  s.failed_in_a_row = r.line_int("integrator.failed_in_a_row", 0, LONG_MAX);
  auto vec = [&](const char* k, Eigen::VectorXd& v) {
    const std::vector<double> x = widened(r.line_doubles(k, n), 1);
    if (x.size() != n) r.fail(std::to_string(x.size()) + " values for a state of " + std::to_string(n));
    v = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(n));
  };
  vec("integrator.y", s.y), vec("integrator.f", s.f), vec("integrator.y_prev", s.y_prev);
  vec("integrator.f_prev", s.f_prev);
  s.interior_c = r.line_doubles("integrator.interior_c", 8);
  for (double c : s.interior_c)
    if (!(c > 0 && c < 1)) r.fail("an interior node must lie strictly inside the step, in (0, 1)");
  const size_t k = s.interior_c.size();
  const std::vector<double> z = widened(r.line_doubles("integrator.interior", k * n), k);
  if (z.size() != k * n)
    r.fail(std::to_string(z.size()) + " values for " + std::to_string(k) + " states of " + std::to_string(n));
  for (size_t i = 0; i < k; ++i)
    s.interior.push_back(Eigen::Map<const Eigen::VectorXd>(z.data() + i * n, static_cast<Eigen::Index>(n)));
  const std::vector<long> c = r.line_longs("integrator.counters", 0, LONG_MAX, 7);
  if (c.size() != 7) r.fail("7 counts expected");
  WorkCounters& w = s.counters;
  w.steps = c[0], w.rejected = c[1], w.rhs = c[2], w.jacobians = c[3], w.factorizations = c[4], w.solves = c[5];
  w.kink_restarts = c[6];
  const std::vector<long> count = r.line_longs("integrator.warnings.count", 0, LONG_MAX, kWarningKinds);
  if (count.size() != kWarningKinds) r.fail(std::to_string(kWarningKinds) + " counts expected");
  const std::vector<double> first_t = r.line_doubles("integrator.warnings.first_t", kWarningKinds);
  if (first_t.size() != kWarningKinds) r.fail(std::to_string(kWarningKinds) + " times expected");
  for (size_t j = 0; j < kWarningKinds; ++j) w.warnings.stat[j] = {count[j], first_t[j]};
}

}  // namespace

void write_state(CheckpointWriter& w, const Model& m, const SimState& s) {
  w.word("part", "drive");
  write_drive(w, m, s.drive);
  w.word("part", "schedule");
  write_schedule(w, s.schedule, s.pending);
  w.word("part", "outputs");
  write_outputs(w, s);
  w.word("part", "integrator");
  write_integrator(w, s.integrator);
}

SimState read_state(CheckpointReader& r, const Scene& sc) {
  SimState s;
  r.line_choice("part", {"drive"});
  s.drive = read_drive(r, sc.model);
  if (s.drive.spray.zones.size() != sc.drive.spray.zones.size())
    r.fail("the drive's " + std::to_string(s.drive.spray.zones.size()) + " spray zones do not fit the scene's " +
           std::to_string(sc.drive.spray.zones.size()));
  r.line_choice("part", {"schedule"});
  read_schedule(r, static_cast<size_t>(sc.model.n_el()), s.schedule, s.pending);
  r.line_choice("part", {"outputs"});
  read_outputs(r, sc, s);
  r.line_choice("part", {"integrator"});
  // before version 14 the arms' and couplings' losses were in the friction integral: a run that
  // tracked energy reads on with the two new integrals at zero, but where the drive has an arm or
  // a coupling its friction figure would hold their losses so far (and its timeseries.csv lacks
  // their columns): refused
  const Model& m = sc.model;
  size_t widen = 0;
  if (r.version() < 14 && m.track_energy) {
    if (m.n_arm() > 0 || m.n_coupling() > 0)
      r.fail(
          "written by an older beltsim, whose energy figures counted the tensioner arms' and couplings' losses "
          "as friction: run the scene again from the start (or resume it with the version that wrote it)");
    widen = kEnergyCount - kDissArms;
  }
  read_integrator(r, static_cast<size_t>(m.n_state()), s.integrator, static_cast<size_t>(2 * m.n_coord() + kDissArms),
                  widen);
  return s;
}

}  // namespace beltsim
