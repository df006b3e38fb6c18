#include "app/cli.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "beltsim_version.hpp"
#include "io/suggest.hpp"
#include "sim/frames.hpp"
#include "sim/run_table.hpp"

namespace beltsim::app {

namespace {

// every --out: a path given empty (an unset shell variable) would silently be the folder beltsim
// runs in
const CLI::Validator kNotEmpty(
    [](std::string& v) {
      return v.empty() ? std::string("an empty path (leave --out out for its default, or give '.' for the folder "
                                     "beltsim runs in)")
                       : std::string();
    },
    "");

void add_set(CLI::App* c, Raw& raw) {
  c->add_option("--set", raw.set,
                "a script parameter, read by the script as beltsim.args.KEY (numbers, true/false, text; repeatable); "
                "a key the script never reads is an error")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
}

void add_safety(CLI::App* c, Raw& raw) {
  c->add_flag("--trusted", raw.trusted,
              "the script gets every Lua library (os.execute, io anywhere, debug, C modules): only for scripts "
              "you trust");
  c->add_option("--max-instructions", raw.max_instructions,
                "Lua instructions per script run or console command (default 1e10; 0: no limit)")
      ->type_name("N");
  c->add_option("--max-lua-memory", raw.max_lua_memory, "Lua heap limit in MiB (default 4096; 0: no limit)")
      ->type_name("MiB");
  c->add_option("--max-lua-wall", raw.max_lua_wall,
                "wall time of each call into Lua (a script run, console command, callback, law; beltsim's own work "
                "not counted) in s (default 600; 0: no limit)")
      ->type_name("S");
  c->add_option("--max-lua-cpu", raw.max_lua_cpu,
                "CPU time of each call into Lua, as --max-lua-wall, in s (default 120; 0: no limit)")
      ->type_name("S");
}

// the option of a run setting (sim/run_table.hpp), its help from the table (out_help for --out)
void add_run_option(CLI::App* c, Raw& raw, const RunSetting& s, const char* out_help) {
  const std::string key(s.key), option(s.option);
  std::string help = s.key == "out" ? std::string(out_help) : std::string(s.note);
  if (!s.unit.empty()) help += " [" + std::string(s.unit) + "]";
  if (s.key == "integrator") help = "one of: " + integrator_list() + " (default " + RunSettings{}.integrator + ")";
  if (s.kind == RunKind::flag) {
    c->add_flag(option, raw.run_flags[key], help);
    return;
  }
  std::string type = key;
  std::transform(type.begin(), type.end(), type.begin(), [](unsigned char ch) { return std::toupper(ch); });
  CLI::Option* o = c->add_option(option, raw.run[key], help)->type_name(type);
  if (s.key == "out") o->check(kNotEmpty);
}

void add_out_and_t_end(CLI::App* c, Raw& raw, const char* out_help) {
  for (const char* key : {"out", "t_end"}) add_run_option(c, raw, *find_run_setting(key), out_help);
}

// every run setting the command line overrides (the table's options)
void add_run_overrides(CLI::App* c, Raw& raw) {
  for (const RunSetting& s : run_settings())
    if (!s.option.empty()) add_run_option(c, raw, s, "output folder (default: out/<script name>)");
  c->add_flag("--no-frames", raw.no_frames, "render no frames and no video, whatever the script asks");
  // its value only as --serve=PORT: join_serve_port makes every --serve that ("--serve 8080" when a
  // number follows, "--serve=0" else), so a script after it is never read as the port
  c->add_option("--serve", raw.serve,
                "watch and steer the run from a browser: a page on 127.0.0.1:PORT (default: a free port), its "
                "address printed at the start; a port in use is refused (docs/live-view.md)")
      ->expected(0, 1)
      ->type_name("[PORT]");
  add_set(c, raw);
  add_safety(c, raw);
}

CLI::App* add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* c =
      app.add_subcommand("render", "draw stored states (a checkpoint, or the states a run kept) to PNGs or a video");
  c->add_option("STATE", o.states,
                "a checkpoint (sim:save), a kept state (OUT/states/state_NNNNN.ckpt), several of them, or a folder of "
                "them (its *.ckpt files)")
      ->required();
  c->add_option("--out", o.out,
                "the PNG to write (a name ending in .png); for several states, or a name ending in /, the folder of "
                "their PNGs (a name not ending in .png)")
      ->type_name("PNG|DIR")
      ->check(kNotEmpty);
  c->add_option("--video", o.video,
                "an MP4 of the states (a name ending in .mp4), one frame each, at the run's frames per second")
      ->type_name("MP4");
  std::string names;
  for (const auto& i : frame_quantities()) names += (names.empty() ? "" : ", ") + std::string(i.key);
  c->add_option("--quantity", o.quantity, "colour the belt by: " + names)->type_name("Q");
  c->add_option("--size", o.size, "picture size in pixels, 16..8192 (even with --video)")->type_name("WxH");
  c->add_option("--view", o.view, "camera centre [m] and visible width [m] (default: the whole layout)")
      ->type_name("X,Y,W");
  c->add_option("--magnify", o.magnify, "factor on the belt's deviation from its path")->type_name("M");
  c->add_option("--range", o.range, "colour-bar range in the quantity's unit")->type_name("LO,HI");
  c->footer(
      "Draws with the renderer of a run's frames, at each state's time, with the run's frame settings\n"
      "(the first state's; the defaults when it drew none) changed by the options. Several states:\n"
      "--out DIR gets DIR/<state name>.png each (so does --out DIR/ for one state), --video one frame\n"
      "each, in the order given (a folder's in the order of their numbers). Every state is read and\n"
      "checked before anything is written. Prints the path of each file written.");
  return c;
}

CLI::App* add_compare_command(CLI::App& app, CompareOptions& o) {
  CLI::App* c = app.add_subcommand("compare", "compare two PNGs (golden images) or two CSV files (results)");
  c->add_option("A", o.a, "the file to check (a run's output)")->required();
  c->add_option("B", o.b, "the reference (a stored PNG or CSV)")->required();
  c->add_option("--tol", o.tol, "PNG: a pixel differs when a channel differs by more than L of 255 levels (default 16)")
      ->type_name("L");
  c->add_option("--max-bad", o.max_bad, "PNG: the images match when at most N pixels differ (default 12)")
      ->type_name("N");
  c->add_option("--diff", o.diff,
                "PNG: the difference image, always written (default: A_diff.png beside A, written when they differ)")
      ->type_name("PNG");
  c->add_option("--mask", o.mask,
                "PNG: leave out W by H pixels from X,Y (pixels, from the top-left corner), clipped to the picture "
                "(repeatable)")
      ->type_name("X,Y,W,H")
      ->allow_extra_args(false);
  c->add_flag("--ignore-text", o.ignore_text,
              "PNG: leave out the text of beltsim's frames (the boxes their PNGs record), for golden frames that "
              "survive a font upgrade");
  c->add_option("--rtol", o.rtol, "CSV: relative tolerance (default 1e-6)")->type_name("R");
  c->add_option("--atol", o.atol,
                "CSV: absolute tolerance, of every column (A) or of the columns of a unit (UNIT=A: N, N.m, m, m/s, "
                "rad, rad/s, J, s, 1); default rtol times the unit's scale (repeatable)")
      ->type_name("[UNIT=]A")
      ->allow_extra_args(false);
  c->add_option("--col-tol", o.col_tol, "CSV: a column's own tolerances (repeatable)")
      ->type_name("NAME=RTOL[,ATOL]")
      ->allow_extra_args(false);
  c->add_option("--skip", o.skip, "CSV: a column left out of the comparison (repeatable)")
      ->type_name("NAME")
      ->allow_extra_args(false);
  c->add_flag("--failing", o.failing, "CSV: after the line, a line for each failing column");
  c->add_flag("--partial", o.partial,
              "CSV: A may span a part of B's times (a short run against the first part of a long one); without it "
              "the two must start and end at the same times");
  c->footer(
      "PNGs: the golden images' metric (a pixel differs when any channel differs by more than L\n"
      "levels), masked pixels left out (dark blue in the difference image). CSVs: columns matched\n"
      "by name; a and b agree when |a - b| <= atol + rtol*max(|a|, |b|),\n"
      "atol by the column's unit (100 N, 10 N.m, 10 rad/s, 1 rad, 0.1 m, 1 m/s, 10 J, 1 s, 0.01 for a\n"
      "ratio, times rtol, unless given); NaN against a number is reported apart; rows aligned on the\n"
      "'t' column: B's rows at A's times, or B interpolated linearly onto A's times when A has times\n"
      "B has not (said on stderr). Prints\n"
      "one line (--failing: and one per failing column); exit 0 when they match, 1 when they differ,\n"
      "2 on bad usage or a file that cannot be read (only regular files are), 3 when the difference\n"
      "image could not be written (the line still says whether they match).");
  return c;
}

// `--serve 8080` as `--serve=8080`, a --serve not followed by a number as `--serve=0` (a free port):
// the word after --serve is its port only when it is a number (CLI11 would take any word)
void join_serve_port(std::vector<std::string>& words) {
  for (size_t i = 0; i < words.size(); ++i) {
    if (words[i] != "--serve") continue;
    const bool port = i + 1 < words.size() && !words[i + 1].empty() &&
                      words[i + 1].find_first_not_of("0123456789") == std::string::npos;
    words[i] += "=" + (port ? words[i + 1] : std::string("0"));
    if (port) words.erase(words.begin() + static_cast<std::ptrdiff_t>(i) + 1);
  }
}

void add_run_command(CLI::App& app, CommandLine& cl) {
  Raw& raw = cl.raw;
  CLI::App* run = app.add_subcommand("run", "run a Lua scenario script");
  run->add_option("SCRIPT", cl.script, "the scenario (Lua)")->required();
  add_run_overrides(run, raw);
  run->footer("The options override the script's scene:run{} settings. Writes DIR/timeseries.csv (samples\n"
              "at fixed times) and DIR/parameters.csv, and the frames (PNG) and video (MP4) a script asks\n"
              "for with scene:run{ frames = {...} }.");
}

void add_wp_command(CLI::App& app, CommandLine& cl) {
  Raw& raw = cl.raw;
  CLI::App* wp = app.add_subcommand("wp", "error against run time of integrators");
  wp->add_option("SCRIPT", cl.script, "the scenario (Lua): its first scene:run{} gives the scene")->required();
  add_out_and_t_end(wp, raw, "output folder (default: out/<script name>/wp)");
  wp->add_option("--integrators", raw.integrators,
                 "those to study, separated by commas (default: esdirk32,trbdf2,cvode; any of: " + integrator_list() +
                     ")")
      ->type_name("A,B,..");
  wp->add_option("--rtols", raw.rtols, "tolerances (default 1e-2,1e-3,1e-4,1e-5,1e-6)")->type_name("R1,R2,..");
  wp->add_option("--ref-integrator", raw.ref_integrator, "integrator of the reference run (default trbdf2)")
      ->type_name("NAME");
  wp->add_option("--ref-rtol", raw.ref_rtol, "tolerance of the reference run (default 1e-7)")->type_name("R");
  wp->add_option("--wall-limit", raw.wall_limit, "a run taking longer is stopped, unfinished (default 120)")
      ->type_name("S");
  wp->add_option("--metric", raw.metric,
                 "also the relative error of this timeseries column at t_end (e.g. driven.creep); the figure "
                 "shows it")
      ->type_name("COLUMN");
  add_set(wp, raw);
  add_safety(wp, raw);
  wp->footer("Runs the script's scene with each integrator at every tolerance, each against the\n"
             "reference. Writes DIR/wp.csv, DIR/wp.png (log-log, gnuplot) and DIR/<integrator>-<rtol>/.");
}

void add_modes_command(CLI::App& app, CommandLine& cl) {
  Raw& raw = cl.raw;
  CLI::App* modes = app.add_subcommand("modes", "natural frequencies, damping and mode shapes; a Campbell diagram");
  modes->add_option("SCRIPT", cl.script, "the scenario (Lua): its first scene:run{} gives the scene and settings")
      ->required();
  // no --t-end: the operating point is --at's (it defaults to the script's t_end)
  add_run_option(modes, raw, *find_run_setting("out"), "output folder (default: out/<script name>/modes)");
  modes->add_option("--at", raw.at, "the operating point: run the scene to T first (default: its t_end; 0: at rest)")
      ->type_name("T");
  modes->add_option("--fmin", raw.fmin, "leave out modes below this frequency (default 1)")->type_name("HZ");
  modes->add_option("--fmax", raw.fmax, "leave out modes above this frequency (default 2000)")->type_name("HZ");
  modes->add_option("--shapes", raw.shapes, "draw the first N modes to DIR/shapes/mode_NN_<f>Hz.png (default 6)")
      ->type_name("N");
  modes->add_option("--check", raw.check,
                    "run the drive on from a push along these modes (numbers as listed) and compare (docs/modes.md)")
      ->type_name("K1,K2,..");
  modes->add_flag("--video", raw.video, "also a video of each drawn mode's cycles (.mp4 beside its PNG)");
  modes->add_option("--campbell", raw.campbell, "sweep this pulley's speed (held at each) for a Campbell diagram")
      ->type_name("PULLEY");
  modes->add_option("--rpm", raw.rpm, "with --campbell: the speeds, FROM:TO:COUNT")->type_name("A:B:N");
  modes->add_option("--orders", raw.orders, "with --campbell: the engine orders drawn (default 2,4)")
      ->type_name("K1,K2,..");
  modes->add_option("--settle", raw.settle, "with --campbell: the run at each speed before its modes (default 0.3)")
      ->type_name("S");
  add_set(modes, raw);
  add_safety(modes, raw);
  modes->footer(
      "Linearizes the drive about its state at T in the space-fixed frame and writes DIR/modes.csv\n"
      "(frequency, damping ratio, each span's, wrap's, pulley's, arm's and rotor's share of the mode's\n"
      "kinetic energy) and the mode shapes' pictures. With --campbell: DIR/campbell.csv and\n"
      "DIR/campbell.png. --at, --shapes, --video and --check go without --campbell, --rpm, --orders\n"
      "and --settle with it. docs/modes.md says how, and what the numbers are checked against.");
}

void add_plot_command(CLI::App& app, CommandLine& cl) {
  Raw& raw = cl.raw;
  CLI::App* plot =
      app.add_subcommand("plot", "draw columns of a timeseries.csv, or of a sweep's summary.csv, to a PNG");
  plot->add_option("CSV", cl.csv,
                   "a timeseries.csv written by run (or the run's folder), or a sweep's summary.csv (or its folder)")
      ->required();
  plot->add_option("COLUMNS", cl.columns,
                   "columns to draw (default: every <pulley>.omega); of a sweep's summary.csv the x column, then y");
  plot->add_option("--out", raw.out, "the PNG (default: plot.png beside the CSV)")->type_name("PNG")->check(kNotEmpty);
  plot->add_option("--from", raw.from, "draw samples with t >= T only [s] (a timeseries.csv only)")->type_name("T");
  plot->add_option("--to", raw.to, "draw samples with t <= T only [s] (a timeseries.csv only)")->type_name("T");
  plot->add_option("--by", raw.by,
                   "a sweep's summary.csv only: one series per value of the column PARAM, its points joined in x order")
      ->type_name("PARAM")
      ->check(kNotEmpty);
  plot->footer(
      "Prints the PNG's path; on a terminal also shows the picture (BELTSIM_TERM_IMAGES=off|symbols|\n"
      "sixel|kitty|iterm forces a mode). Columns of two units share the plot on two y axes. A sweep's\n"
      "points without a mark (failed, not run) are named on stderr. E.g. beltsim plot out/study\n"
      "pretension 'slip_max [1]' --by load: slip_max against pretension, a line per load.");
}

void add_summary_command(CLI::App& app, CommandLine& cl) {
  Raw& raw = cl.raw;
  CLI::App* summary = app.add_subcommand("summary", "review figures of a run over a time window");
  summary->add_option("DIR", cl.csv, "a run's output folder (its timeseries.csv and parameters.csv)")->required();
  summary->add_option("--from", raw.from, "the window's start [s] (default: the first sample)")->type_name("T0");
  summary->add_option("--to", raw.to, "the window's end [s] (default: the last sample)")->type_name("T1");
  summary->add_option("--csv", raw.csv_out, "also write the figures to this CSV (a header and one row)")
      ->type_name("FILE")
      ->check(kNotEmpty);
  summary->add_option("--plot", raw.plot_out, "also draw the window's span tensions, arm angles and rotor speeds")
      ->type_name("PNG")
      ->check(kNotEmpty);
  summary->footer(
      "Per span the tension's mean, min and max; per pulley its mean speed, slip, slip arc, capstan\n"
      "margin (T1/T2 against e^(mu*theta) at each sample, mu that of the wrap's elements then: its\n"
      "least and mean) and hub load; tensioner arms' swing, decouplers' overruns,\n"
      "the belt's power loss by channel (with energy = true). docs/summary.md says how each is made.");
}

void add_console_command(CLI::App& app, CommandLine& cl) {
  Raw& raw = cl.raw;
  CLI::App* console = app.add_subcommand("console", "an interactive Lua console with a live simulation");
  console->add_option("SCRIPT", cl.console_script, "a scenario to load first");
  add_run_overrides(console, raw);
  console->footer("Arguments after -- are passed to the script.");
}

void add_sweep_command(CLI::App& app, CommandLine& cl) {
  Raw& raw = cl.raw;
  CLI::App* sweep = app.add_subcommand("sweep", "run a sweep: many points, each a run, on every core or on Slurm");
  sweep->add_option("FILE", cl.script, "a sweep file (returns beltsim.sweep{...}), or a script with --set lists")
      ->required();
  sweep->add_option("--out", raw.out, "the sweep's folder (default: out/<file name>)")
      ->type_name("DIR")
      ->check(kNotEmpty);
  sweep->add_option("--jobs", raw.jobs, "points run at once (default: the processors this process may use)")
      ->type_name("N");
  sweep->add_option("--point", raw.point, "run point K alone, in this process (0-based, as --list numbers them)")
      ->type_name("K");
  sweep->add_flag("--list", raw.list, "print the points (CSV) and run nothing");
  sweep->add_flag("--collect", raw.collect, "merge the points' results into summary.csv and run nothing");
  sweep->add_flag("--rerun", raw.rerun, "run every point again, done or not (with --slurm: every point in the array)");
  sweep->add_option("--set", raw.set,
                    "the quick form: FILE is an ordinary script and each KEY=V1,V2,.. one parameter "
                    "(beltsim.args.KEY); the lists are crossed, the first varying slowest (repeatable)")
      ->type_name("KEY=V1,V2,..")
      ->allow_extra_args(false);
  sweep->add_flag("--slurm", raw.slurm, "write DIR/sweep.sbatch (a job array) and DIR/collect.sbatch, run nothing");
  sweep->add_flag("--submit", raw.submit, "with --slurm: submit both with sbatch and print the job ids");
  sweep->add_option("--partition", raw.partition, "with --slurm: the partition")->type_name("P");
  sweep->add_option("--time", raw.time, "with --slurm: each task's time limit (Slurm's format, e.g. 30 or 1:00:00)")
      ->type_name("T");
  sweep->add_option("--max-parallel", raw.max_parallel, "with --slurm: tasks running at once (--array=..%M)")
      ->type_name("M");
  add_safety(sweep, raw);
  sweep->footer("Each point runs in a process of its own with its folder DIR/<point>/ (point.csv: its parameters,\n"
                "status, inputs and figures; log.txt: its messages); DIR/summary.csv merges them. Run again:\n"
                "the points not ok, or run with other files, program or --trusted, run. Exit status 0 when\n"
                "every point is ok, 1 otherwise. docs/sweeps.md.");
}

// the message of a parse error: an extra word or a misspelt option named with the command's
// closest option, an option of one value given twice
std::string parse_error_message(const CLI::App& app, const CLI::ParseError& e) {
  const CLI::App* sub = app.get_subcommands().empty() ? nullptr : app.get_subcommands().front();
  const std::string name = sub ? sub->get_name() : "";
  std::string msg = e.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    std::string extra, hint;
    std::vector<std::string> options;  // the command's own, for a misspelt one
    if (sub)
      for (const CLI::Option* o : sub->get_options())
        for (const std::string& l : o->get_lnames()) options.push_back("--" + l);
    for (const auto& w : app.remaining(true)) {
      extra += (extra.empty() ? "" : " ") + w;
      if (hint.empty() && w.rfind("--", 0) == 0) hint = did_you_mean(w.substr(0, w.find('=')), options);
    }
    msg = (sub ? name + " does not take: " : "unexpected: ") + extra + hint +
          (name == "console" ? " (arguments for the script go after --)" : "");
  }
  // an option of one value given more than once: CLI11 says "--t-end: At Most 1 required but
  // received 2"
  if (constexpr std::string_view at_most = ": At Most 1 required but received ";
      dynamic_cast<const CLI::ArgumentMismatch*>(&e) && msg.find(at_most) != std::string::npos) {
    const std::string option = msg.substr(0, msg.find(at_most)), times = msg.substr(msg.find(at_most) + at_most.size());
    msg = option + " given " + (times == "2" ? std::string("twice") : times + " times") + ": give it once";
  }
  return msg;
}

// a flag of the command given a value ("--check=banana", "--trusted=2"): CLI11 reads the value as
// a boolean, so a word it cannot convert got its raw "Could not convert: --check = banana" and any
// number but 0 turned the flag on, the sandbox's --trusted too, without a word. A flag takes no
// value: the message, or "" when every flag is given alone
std::string flag_given_a_value(const CLI::App& app, const std::vector<std::string>& words) {
  if (words.empty()) return "";
  const CLI::App* sub = nullptr;
  try {
    sub = app.get_subcommand(words[0]);
  } catch (const CLI::OptionNotFound&) {
    return "";
  }
  for (size_t i = 1; i < words.size(); ++i) {
    const std::string& w = words[i];
    const size_t eq = w.find('=');
    if (w.rfind("--", 0) != 0 || eq == std::string::npos) continue;
    const std::string name = w.substr(0, eq);
    const CLI::Option* o = sub->get_option_no_throw(name);
    if (o && o->get_expected_max() == 0)
      return name + " takes no value (got '" + w + "'): give " + name + " alone to turn it on, or leave it out";
  }
  return "";
}

}  // namespace

std::optional<CommandLine> parse_command_line(int argc, char** argv, int* status) {
  CLI::App app{"beltsim: belt transmissions, the discrete model of K. Kubas; scenarios are Lua scripts.", "beltsim"};
  app.set_version_flag("--version", std::string("beltsim ") + kBeltsimVersion);
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 on success, 1 on a script, parameter, run or plot error, an input file that is\n"
      "missing or unreadable (compare: 2) or an output that could not be written, 2 on bad usage,\n"
      "130 after Ctrl-C, 143 after SIGTERM, 129 after SIGHUP (outputs closed). 'beltsim COMMAND\n"
      "--help' describes a command; 'beltsim help parameters' lists the scene's parameters with their\n"
      "units and defaults, 'beltsim help run-settings' the run's.");
  const auto fail = [&](int s) {
    *status = s;
    return std::optional<CommandLine>();
  };
  CommandLine cl;
  add_run_command(app, cl);
  add_wp_command(app, cl);
  add_modes_command(app, cl);
  add_plot_command(app, cl);
  add_summary_command(app, cl);
  add_render_command(app, cl.render);
  add_compare_command(app, cl.compare);
  add_console_command(app, cl);
  add_sweep_command(app, cl);

  // `beltsim console ... -- ARGS`: everything after the first -- belongs to the script
  std::vector<std::string> words(argv + 1, argv + argc);
  if (!words.empty() && words[0] == "console") {
    const auto dd = std::find(words.begin(), words.end(), "--");
    if (dd != words.end()) {
      cl.console_args.assign(dd + 1, words.end());
      words.erase(dd, words.end());
    }
  }
  join_serve_port(words);
  if (words.size() == 2 && words[0] == "help" && words[1] == "parameters") {
    // the scene's parameter tables, as docs/lua-api.md holds them (scene/parameters.hpp)
    cl.command = "help-parameters";
    return cl;
  }
  if (words.size() == 2 && words[0] == "help" && words[1] == "run-settings") {
    // the run settings' table, as docs/lua-api.md holds it (sim/run_table.hpp)
    cl.command = "help-run-settings";
    return cl;
  }
  if (!words.empty() && words[0] == "help") {
    // `beltsim help` alone is --help; a topic it does not have is bad usage, not the general help
    const std::vector<std::string> topics{"parameters", "run-settings"};
    if (words.size() > 1) {
      const std::string asked = join(std::vector<std::string>(words.begin() + 1, words.end()), " ");
      std::fprintf(stderr,
                   "beltsim: help has no topic '%s'%s (topics: %s)\nRun 'beltsim --help' for the usage, "
                   "'beltsim COMMAND --help' for a command's.\n",
                   asked.c_str(), did_you_mean(asked, topics).c_str(), join(topics).c_str());
      return fail(2);
    }
    words[0] = "--help";
  }
  const std::vector<std::string> commands{"run", "wp", "modes", "plot", "summary", "render", "compare", "console", "sweep"};
  if (!words.empty() && !words[0].empty() && words[0][0] == '-' && words[0] != "-h" && words[0] != "--help" &&
      words[0] != "--version") {
    std::fprintf(stderr, "beltsim: unknown option '%s' before the command\nRun 'beltsim --help' for the usage.\n",
                 words[0].c_str());
    return fail(2);
  }
  if (!words.empty() && (words[0].empty() || words[0][0] != '-') &&
      std::find(commands.begin(), commands.end(), words[0]) == commands.end()) {
    std::fprintf(stderr, "beltsim: unknown command '%s'%s (commands: %s)\nRun 'beltsim --help' for the usage.\n",
                 words[0].c_str(), did_you_mean(words[0], commands).c_str(), join(commands).c_str());
    return fail(2);
  }
  if (const std::string m = flag_given_a_value(app, words); !m.empty()) {
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim %s --help' for the usage.\n", m.c_str(), words[0].c_str());
    return fail(2);
  }
  std::reverse(words.begin(), words.end());  // CLI11 takes the arguments in reverse order
  try {
    app.parse(words);
  } catch (const CLI::CallForHelp& e) {
    return fail(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return fail(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return fail(app.exit(e));
  } catch (const CLI::ParseError& e) {
    const CLI::App* sub = app.get_subcommands().empty() ? nullptr : app.get_subcommands().front();
    const std::string name = sub ? sub->get_name() : "";
    const std::string msg = parse_error_message(app, e);
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim%s --help' for the usage.\n", msg.c_str(),
                 name.empty() ? "" : (" " + name).c_str());
    return fail(2);
  }

  cl.command = app.get_subcommands().front()->get_name();
  return cl;
}
}  // namespace beltsim::app
