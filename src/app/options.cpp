#include "app/options.hpp"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <tuple>
#include <utility>

#include "integrate/integrator.hpp"
#include "integrate/stepper.hpp"
#include "io/output_dir.hpp"
#include "script/script_args.hpp"
#include "sim/run_table.hpp"

namespace beltsim::app {

double number(const std::string& option, const std::string& text) {
  const auto x = script::decimal(text);
  if (!x) throw UsageError(option + " needs a finite decimal number, got '" + text + "'");
  return *x;
}

void require_png(const std::string& option, const std::string& path) {
  if (const std::string bad = png_name_problem(path); !bad.empty()) throw UsageError(option + " " + path + ": " + bad);
}

namespace {

// each comma-separated item a number in (0, 1)
std::vector<double> tolerances(const std::string& option, const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto x = script::decimal(item);
    if (!x) throw UsageError(option + " needs numbers in (0, 1) separated by commas, got '" + text + "'");
    if (const std::string bad = rtol_problem(*x); !bad.empty())
      throw UsageError(option + ": each " + bad);
    out.push_back(*x);
  }
  if (out.empty() || (!text.empty() && text.back() == ','))
    throw UsageError(option + " needs numbers in (0, 1) separated by commas, got '" + text + "'");
  return out;
}

// a name of an integrator (integrate/stepper.hpp), else a UsageError
void known_integrator(const std::string& name) {
  try {
    beltsim::check_integrator(name);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

std::string integrator_list() {
  std::string names;
  for (const auto& n : integrator_names()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

int whole_number(const std::string& option, const std::string& text, int lo) {
  // (a word is refused as what is wanted, a whole number: "needs a finite decimal number" misled)
  const auto x = script::decimal(text);
  if (!x || !(*x == std::floor(*x) && *x >= lo && *x <= 1e9))
    throw UsageError(option + " must be a whole number >= " + std::to_string(lo) + ", got " + text);
  return static_cast<int>(*x);
}

script::Safety safety(const Raw& raw) {
  script::Safety s;
  s.trusted = raw.trusted;
  if (raw.max_instructions) {
    const double x = number("--max-instructions", *raw.max_instructions);
    if (!(x >= 0 && x == std::floor(x) && x <= 1e18))
      throw UsageError("--max-instructions must be a whole number in [0, 1e18] (0: no limit), got " +
                       *raw.max_instructions);
    s.max_instructions = static_cast<std::uint64_t>(x);
  }
  if (raw.max_lua_memory) {
    const double x = number("--max-lua-memory", *raw.max_lua_memory);
    if (!(x >= 0 && x <= 1e9))
      throw UsageError("--max-lua-memory must be in [0, 1e9] MiB (0: no limit), got " + *raw.max_lua_memory);
    s.max_lua_memory = static_cast<std::size_t>(x * (1 << 20));
    if (x > 0 && s.max_lua_memory < (std::size_t(1) << 20))
      throw UsageError("--max-lua-memory must be at least 1 MiB (0: no limit), got " + *raw.max_lua_memory);
  }
  for (auto [option, text, value] : {std::tuple{"--max-lua-wall", &raw.max_lua_wall, &s.max_lua_wall},
                                     std::tuple{"--max-lua-cpu", &raw.max_lua_cpu, &s.max_lua_cpu}}) {
    if (!*text) continue;
    const double x = number(option, **text);
    if (!(x >= 0 && x <= 1e9))
      throw UsageError(std::string(option) + " must be in [0, 1e9] s (0: no limit), got " + **text);
    *value = x;
  }
  return s;
}

std::vector<std::string> safety_words(const Raw& raw) {
  std::vector<std::string> w;
  if (raw.trusted) w.push_back("--trusted");
  for (auto [option, text] :
       {std::pair{"--max-instructions", &raw.max_instructions}, std::pair{"--max-lua-memory", &raw.max_lua_memory},
        std::pair{"--max-lua-wall", &raw.max_lua_wall}, std::pair{"--max-lua-cpu", &raw.max_lua_cpu}})
    if (*text) w.insert(w.end(), {option, **text});
  return w;
}

std::vector<std::string> run_option_words(const Raw& raw) {
  std::vector<std::string> w;
  for (const RunSetting& s : run_settings()) {
    if (s.option.empty() || s.key == "out") continue;
    const std::string key(s.key), option(s.option);
    if (s.kind == RunKind::flag) {
      if (const auto it = raw.run_flags.find(key); it != raw.run_flags.end() && it->second) w.push_back(option);
    } else if (const auto it = raw.run.find(key); it != raw.run.end() && it->second) {
      w.insert(w.end(), {option, *it->second});
    }
  }
  if (raw.no_frames) w.push_back("--no-frames");
  const std::vector<std::string> safe = safety_words(raw);
  w.insert(w.end(), safe.begin(), safe.end());
  return w;
}

std::vector<std::string> run_option_keys() {
  std::vector<std::string> keys;
  for (const RunSetting& s : run_settings())
    if (!s.option.empty()) keys.emplace_back(s.key);
  return keys;
}

script::Overrides overrides(const Raw& raw, std::vector<std::string> option_keys) {
  script::Overrides o;
  o.option_keys = std::move(option_keys);
  // each option of the run-settings table given, read by its kind and checked by its setting's rule
  for (const RunSetting& s : run_settings()) {
    if (s.option.empty()) continue;
    const std::string key(s.key), option(s.option);
    const RunSlot v = run_slot(s, o.run);
    if (auto* f = std::get_if<bool*>(&v)) {
      if (const auto it = raw.run_flags.find(key); it != raw.run_flags.end() && it->second) **f = true, o.give(key);
      continue;
    }
    const auto it = raw.run.find(key);
    if (it == raw.run.end() || !it->second) continue;
    if (auto* x = std::get_if<double*>(&v)) **x = number(option, *it->second);
    if (auto* t = std::get_if<std::string*>(&v)) **t = *it->second;
    if (const std::string bad = run_problem(s, o.run, true); !bad.empty()) throw UsageError(option + (s.kind == RunKind::text ? ": " : " ") + bad);
    o.give(key);
  }
  if (raw.serve) {
    o.serve = raw.serve->empty() ? 0 : whole_number("--serve", *raw.serve, 0);
    if (*o.serve > 65535) throw UsageError("--serve: a port in 0..65535 (0: a free one), got " + *raw.serve);
  }
  o.no_frames = raw.no_frames;
  try {
    o.set = script::parse_sets(raw.set);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return o;
}

WpSettings wp_settings(const Raw& raw) {
  WpSettings wps;
  if (raw.integrators) {
    std::stringstream ss(*raw.integrators);
    std::string item;
    while (std::getline(ss, item, ',')) {
      known_integrator(item);
      wps.integrators.push_back(item);
    }
    if (wps.integrators.empty()) throw UsageError("--integrators needs names separated by commas");
  }
  if (raw.rtols) wps.rtols = tolerances("--rtols", *raw.rtols);
  if (raw.ref_integrator) {
    known_integrator(*raw.ref_integrator);
    wps.ref_integrator = *raw.ref_integrator;
  }
  if (raw.ref_rtol) {
    const double x = number("--ref-rtol", *raw.ref_rtol);
    if (const std::string bad = rtol_problem(x); !bad.empty()) throw UsageError("--ref-rtol " + bad);
    wps.ref_rtol = x;
  }
  if (raw.metric) {
    if (raw.metric->empty()) throw UsageError("--metric needs a column name, e.g. --metric driven.creep");
    wps.metric = *raw.metric;
  }
  if (raw.wall_limit) {
    const double x = number("--wall-limit", *raw.wall_limit);
    if (!(x > 0)) throw UsageError("--wall-limit must be > 0 s, got " + *raw.wall_limit);
    wps.wall_limit = x;
  }
  return wps;
}

}  // namespace beltsim::app
