// `beltsim run`, `beltsim wp` and `beltsim console`: a script run by the interpreter (commands.hpp).
#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "io/output_dir.hpp"
#include "plot/wp_plot.hpp"
#include "script/console.hpp"
#include "script/docall.hpp"
#include "script/interpreter.hpp"
#include "script/signals.hpp"

namespace beltsim::app {

namespace fs = std::filesystem;

using script::stop_flag;
using script::stop_signal;
using script::stopped_status;

int cmd_run(const std::string& script, const script::Overrides& o, const script::Safety& s) {
  try {
    script::Interpreter lua(s);
    const script::Interruptible on_signal(lua);
    lua.set_overrides(o);
    lua.set_stop_flag(&stop_flag());
    if (o.serve) lua.serve(*o.serve);
    lua.run_file(script);
    if (lua.interrupted() || stop_signal() != 0) return stopped_status();
    // a --set the script never read: the run did not use what was asked of it
    const std::vector<std::string> unread = lua.unread_args(script);
    for (const std::string& m : unread) std::fprintf(stderr, "beltsim: %s\n", m.c_str());
    if (!unread.empty()) return 1;
  } catch (const script::ScriptError& e) {
    std::fprintf(stderr, "beltsim: %s\n%s", e.what(), script::shown_traceback(e.traceback).c_str());
    mark_output_failure_shown(e.what());  // an output lost, named here with the script's line: not again at exit
    return stop_signal() != 0 ? stopped_status() : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return stop_signal() != 0 ? stopped_status() : 1;
  }
  return 0;
}

script::Captured capture_first_run(script::Interpreter& lua, const std::string& script, const script::Overrides& o,
                                   const char* command, bool t_end_to_script) {
  script::Captured cap;
  cap.command = command;
  script::Overrides captured;  // --out is the command's own folder
  if (t_end_to_script && o.has("t_end")) captured.run.t_end = o.run.t_end, captured.give("t_end");
  captured.set = o.set;
  captured.option_keys = o.option_keys;
  lua.set_overrides(captured);
  lua.set_capture(&cap);
  lua.run_file(script);
  if (!cap.scene) throw std::runtime_error(script + ": the script never calls scene:run{}");
  for (const std::string& m : lua.unread_args(script))
    std::fprintf(stderr, "beltsim %s: warning: %s (before its first scene:run{})\n", command, m.c_str());
  return cap;
}

int cmd_wp(const std::string& script, const script::Overrides& o, const script::Safety& s,
           WpSettings wps) {
  try {
    script::Interpreter lua(s);
    const script::Interruptible on_signal(lua);
    const script::Captured cap = capture_first_run(lua, script, o, "wp", true);
    wps.base = cap.settings;
    wps.base.out_dir = o.has("out") ? o.run.out_dir : (fs::path(script::default_out_dir(script)) / "wp").string();
    const WpResult r = work_precision(*cap.scene, wps, &stop_flag());
    const std::string png = (fs::path(wps.base.out_dir) / "wp.png").string();
    std::string drawn;
    try {
      plot::plot_wp_png(r, png);
      drawn = png;
    } catch (const std::exception& e) {  // the CSV is the result; the picture is a convenience
      std::fprintf(stderr, "beltsim wp: no plot: %s\n", e.what());
      mark_output_failure_shown(e.what());  // (a picture that cannot be written fails the command)
    }
    std::fprintf(stderr, "beltsim wp: wrote %s%s%s\n", r.csv_path.c_str(), drawn.empty() ? "" : " and ", drawn.c_str());
    return stop_signal() != 0 ? stopped_status() : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return stop_signal() != 0 ? stopped_status() : 1;
  }
}

int cmd_console(const std::optional<std::string>& script, const std::vector<std::string>& args,
                const script::Overrides& o, const script::Safety& s, const Environment& env,
                const std::vector<std::string>& replay_options) {
  try {
    return script::run_console(script, args, o, s, {env.history, env.images, replay_options});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return 1;
  }
}

}  // namespace beltsim::app
