// beltsim: reads the command line (cli.hpp), the environment (environment.hpp), runs the command.
// Every number on the command line is a finite decimal (no hex, inf or nan); an option a command
// does not take is an error. Exit status: 0 on success, 1 on a script, parameter, run or plot
// error, an input file that is missing or unreadable, or an output that could not be written
// (message on stderr, outputs written so far kept; compare: 0 when the files match, 1 when they
// differ, 2 when they could not be compared, a file unreadable too, 3 when the difference image
// could not be written), 2 on bad usage (or an environment variable it cannot read, or a CPU
// without the instruction set it was built for: isa_check.cpp), 130 when stopped by Ctrl-C
// (SIGINT), 143 by SIGTERM and 129 by SIGHUP (outputs closed; script/signals.hpp).
#include <csignal>
#include <cstdio>
#include <string>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/environment.hpp"
#include "io/output_dir.hpp"
#include "scene/parameters.hpp"
#include "script/signals.hpp"
#include "sim/run_table.hpp"

namespace {

// An output that could not be written (io/output_dir.hpp records each) fails the command, also
// when no message of its own said so (a simulation closed at the interpreter's end, a script that
// caught the error): each not shown yet is named, and a status of 0 becomes 1.
int with_outputs(int status) {
  for (const std::string& m : beltsim::unshown_output_failures()) std::fprintf(stderr, "beltsim: %s\n", m.c_str());
  return status == 0 && !beltsim::output_failures().empty() ? 1 : status;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace beltsim::app;
  // A file-size limit (`ulimit -f`, a batch system's) sends SIGXFSZ at the write that passes it,
  // whose default action kills the process mid-row, silently; ignored, that write(2) fails with
  // EFBIG as on a full disk, and the output's error names the file, keeps whole rows and fails the
  // command (a user's trial: exit 153, a row cut in two, no end rows in parameters.csv)
  std::signal(SIGXFSZ, SIG_IGN);
  int status = 0;
  const std::optional<CommandLine> cl = parse_command_line(argc, argv, &status);
  if (!cl) return status;
  if (cl->command == "help-parameters") {
    // the scene's parameter tables, as docs/lua-api.md holds them (scene/parameters.hpp)
    std::fputs(beltsim::parameters_markdown().c_str(), stdout);
    return 0;
  }
  if (cl->command == "help-run-settings") {
    std::fputs(beltsim::run_settings_markdown().c_str(), stdout);
    return 0;
  }

  Environment env;
  try {
    env = read_environment();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    return 2;
  }
  apply_render_settings(env);

  const std::string& c = cl->command;
  const Raw& raw = cl->raw;
  try {
    if (c == "compare") return with_outputs(cmd_compare(cl->compare));
    if (c == "summary") return with_outputs(cmd_summary(cl->csv, raw));
    if (c == "plot") return with_outputs(cmd_plot(cl->csv, cl->columns, raw, env.images));  // a signal ends it at once: nothing to close
    beltsim::script::install_stop_signals();
    if (c == "render") return with_outputs(cmd_render(cl->render));  // stops between two states
    if (c == "run") return with_outputs(cmd_run(cl->script, overrides(raw), safety(raw)));
    if (c == "modes") return with_outputs(cmd_modes(cl->script, overrides(raw, {"out"}), safety(raw), raw));
    if (c == "sweep") return with_outputs(cmd_sweep(cl->script, raw, safety(raw)));
    if (c == "console")
      return with_outputs(
          cmd_console(cl->console_script, cl->console_args, overrides(raw), safety(raw), env, run_option_words(raw)));
    return with_outputs(cmd_wp(cl->script, overrides(raw, {"out", "t_end"}), safety(raw), wp_settings(raw)));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim %s --help' for the usage.\n", e.what(), c.c_str());
    return 2;
  }
}
