#!/usr/bin/env python3
"""`--set KEY=VALUE` on the command line: beltsim.args in run, console and wp, the checks of the
values (exit 2), and a key the script never read (exit 1 naming it, with a suggestion). What a
user sees when a script fails (file:line and Lua's traceback), is a folder, or the environment
names a value beltsim does not know (src/app/environment.cpp); an empty --out or out is refused."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None


def run(args, stdin=None, cwd=None):
    p = subprocess.run([BELTSIM] + args, input=stdin, capture_output=True, text=True, cwd=cwd, timeout=120)
    return p.returncode, p.stdout, p.stderr


class Start(unittest.TestCase):
    def test_video_and_gl_libraries_are_opened_when_needed_not_at_start(self):
        # FFmpeg's and Mesa's libraries pull in over a hundred others, whose loading took most of
        # the start of every beltsim process: they are opened by the first video or GL context
        # (src/media/shared_library.hpp), not linked
        p = subprocess.run(["ldd", BELTSIM], capture_output=True, text=True, timeout=60)
        self.assertEqual(p.returncode, 0, p.stderr)
        for library in ("libavcodec", "libavformat", "libswscale", "libOSMesa", "libEGL", "libLLVM"):
            self.assertNotIn(library, p.stdout)


class SetOption(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_cli_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.script = os.path.join(self.dir, "args.lua")
        with open(self.script, "w") as f:
            f.write("local a = beltsim.args\n"
                    "print(a.elements, math.type(a.elements), a.mu, a.wet, a.name)\n")

    def test_values_reach_the_script(self):
        code, out, err = run(["run", self.script, "--set", "elements=120", "--set", "mu=0.3",
                              "--set", "wet=true", "--set", "name=esdirk32"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out.split(), ["120", "integer", "0.3", "true", "esdirk32"])

    def test_unread_key_is_an_error_naming_it(self):
        code, out, err = run(["run", self.script, "--set", "elemnts=120"], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("--set elemnts=120 was never read by " + self.script + " (did you mean 'elements'?); "
                      "keys it read: elements, mu, wet, name", err)

    def test_unread_key_that_names_an_option_suggests_it(self):
        # trial 12: --set rtol=1e-3 for --rtol 1e-3 was told the keys the script read, not the option
        for key, value, option in [("rtol", "1e-3", "--rtol 1e-3"), ("t_end", "0.1", "--t-end 0.1"),
                                   ("integrator", "esdirk32", "--integrator esdirk32"), ("check", "true", "--check"),
                                   ("max_wall", "5", "--max-wall 5")]:
            code, out, err = run(["run", self.script, "--set", key + "=" + value], cwd=self.dir)
            self.assertEqual(code, 1, err)
            self.assertIn("--set %s=%s was never read by %s (did you mean the option %s?); keys it read: "
                          "elements, mu, wet, name" % (key, value, self.script, option), err)
        # a key no option of the command names: no option suggested (wp takes --rtols, not --rtol)
        path = os.path.join(self.dir, "batch.lua")
        with open(path, "w") as f:
            f.write(two_pulley(elements=30) + 'drive:run { t_end = 0.002, progress = false }\n')
        code, out, err = run(["wp", path, "--set", "rtol=1e-3", "--integrators", "trbdf2", "--rtols", "1e-2",
                              "--ref-rtol", "1e-3", "--out", os.path.join(self.dir, "wp")], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("--set rtol=1e-3 was never read by " + path + "; keys it read: none", err)
        self.assertNotIn("did you mean the option", err)
        # a live simulation's start: --t-end does not set its end (trial 23 followed the hint, and the
        # run still stopped where its run_to said), so no option is suggested for t_end; --rtol is
        path = os.path.join(self.dir, "live.lua")
        with open(path, "w") as f:
            f.write(two_pulley(elements=30) + 'local sim = drive:start { progress = false }\n'
                    'sim:run_to(beltsim.args.t_end or 0.002)\n')
        for key, value, meant in [("t_end", "0.004", ""), ("rtol", "1e-3", " (did you mean the option --rtol 1e-3?)")]:
            code, out, err = run(["run", path, "--set", key + "=" + value, "--out", os.path.join(self.dir, "live")],
                                 cwd=self.dir)
            self.assertEqual(code, 1, err)
            self.assertIn("start: the simulation was not started: --set %s=%s has not been read by %s before its first "
                          "run or start%s; keys it read: none" % (key, value, path, meant), err)

    def test_unread_key_fails_the_first_run_before_it_integrates(self):
        # issue 29: a misspelt key used to cost the whole simulation before the error
        path = os.path.join(self.dir, "runs.lua")
        with open(path, "w") as f:
            f.write("local e = beltsim.args.elements or 30\n" + SCENE.replace("elements = 30", "elements = e")
                    .replace("local sim = drive:start { progress = false, out = \"out\" }",
                             "drive:run { t_end = 5, progress = false, out = \"out\" }"))
        code, out, err = run(["run", path, "--set", "elements=30", "--set", "rtoll=1e-3"], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("run: nothing was integrated: --set rtoll=1e-3 has not been read by " + path +
                      " before its first run or start", err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "out", "timeseries.csv")), err)
        # scene:start integrates nothing itself: its refusal says it did not start (a user read 'nothing
        # was integrated' from a call that never integrates)
        with open(path, "w") as f:
            f.write("local e = beltsim.args.elements or 30\n" + SCENE.replace("elements = 30", "elements = e"))
        code, out, err = run(["run", path, "--set", "elements=30", "--set", "rtoll=1e-3"], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("start: the simulation was not started: --set rtoll=1e-3 has not been read by " + path +
                      " before its first run or start", err)

    def test_values_that_start_like_numbers_must_be_numbers(self):
        for value in ["0x10", "1e", "-inf", "+nan", "2s", ".5.5"]:
            code, out, err = run(["run", self.script, "--set", "elements=" + value], cwd=self.dir)
            self.assertEqual(code, 2, value + ": " + err)
            self.assertIn("--set elements=" + value + ": a value that starts like a number", err)
        code, out, err = run(["run", self.script, "--set", "elements=1", "--set", "elements=2"], cwd=self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("elements is set twice", err)

    def test_console_and_a_command_that_takes_none(self):
        code, out, err = run(["console", self.script, "--set", "elements=48"], stdin="print(beltsim.args.elements * 2)\n",
                             cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("96", out)
        code, out, err = run(["plot", os.path.join(self.dir, "x.csv"), "--set", "a=1"], cwd=self.dir)
        self.assertEqual(code, 2, err)


class HelpParameters(unittest.TestCase):
    """`beltsim help parameters`: the scene's parameter tables (the same text docs/lua-api.md holds,
    checked there by Parameters.TheDocsHoldTheTable)."""

    def test_prints_the_tables(self):
        code, out, err = run(["help", "parameters"])
        self.assertEqual(code, 0, err)
        self.assertIn("| `mass_per_length` | kg/m | `0.096` (the paper's) | > 0 |", out)
        self.assertIn("| `damping` | N·s/m | `300` (the paper's) | ≥ 0 |", out)
        with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "lua-api.md"),
                  encoding="utf-8") as f:
            self.assertIn(out, f.read())

    def test_a_topic_it_does_not_have_is_bad_usage(self):
        # once printed the general help and exited 0, so a typo looked like an answer
        for args, what in [(["help", "foo"], "beltsim: help has no topic 'foo' (topics: parameters, run-settings)"),
                           (["help", "parameter"], "help has no topic 'parameter' (did you mean 'parameters'?)"),
                           (["help", "parameters", "x"], "help has no topic 'parameters x'")]:
            code, out, err = run(args)
            self.assertEqual(code, 2, err)
            self.assertIn(what, err)
            self.assertEqual(out, "")
        code, out, err = run(["help"])  # alone: the general help
        self.assertEqual(code, 0, err)
        self.assertIn("Usage: beltsim", out)


SCENE = two_pulley(elements=30) + 'local sim = drive:start { progress = false, out = "out" }\n'


class Errors(unittest.TestCase):
    """What a user sees when a script, its path, an option or the environment is wrong."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_cli_")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def script(self, text, name="s.lua"):
        path = os.path.join(self.dir, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def test_t_end_leaves_out_what_comes_after_it(self):
        # a quick --t-end check of a script whose snapshots and frames come later runs, saying so
        path = self.script(two_pulley(elements=30) +
                           'drive:run { t_end = 0.5, progress = false, out = "out", snapshots = { times = {0.001, 0.3} },\n'
                           '            frames = { t_start = 0.2, png = true } }\n')
        code, out, err = run(["run", path, "--t-end", "0.003"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("beltsim: snapshots: the snapshot at 0.3 s is after t_end = 0.003 s (from --t-end): skipped", err)
        self.assertIn("beltsim: frames: they start at 0.2 s, after t_end = 0.003 s (from --t-end): none drawn", err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "out", "frames")), err)

    def test_a_sample_longer_than_the_run_is_warned_of(self):
        # trial 16: sample = 1 (meant 1 ms) on a 0.2 s run wrote a timeseries.csv of the row at t = 0
        # alone, without a word
        path = self.script(two_pulley(elements=30) + 'drive:run { t_end = 0.004, sample = 0.01, progress = false, out = "out" }\n')
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("beltsim: warning: run.sample = 0.01 s is longer than t_end = 0.004 s: timeseries.csv will hold "
                      "only the row at t = 0 (the interval is in seconds: 1 ms is sample = 0.001)", err)
        with open(os.path.join(self.dir, "out", "timeseries.csv")) as f:
            self.assertEqual(len(f.readlines()), 2)
        # a --t-end that shortens the run below it is named
        path = self.script(two_pulley(elements=30) + 'drive:run { t_end = 0.5, sample = 0.01, progress = false, out = "out" }\n')
        code, out, err = run(["run", path, "--t-end", "0.004"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("run.sample = 0.01 s is longer than t_end = 0.004 s (from --t-end): ", err)
        code, out, err = run(["run", path, "--t-end", "0.01"], cwd=self.dir)  # two rows: no warning
        self.assertEqual(code, 0, err)
        self.assertNotIn("run.sample", err)

    def test_a_misspelt_command_or_option_gets_a_suggestion(self):
        for args, what in [(["runn", "x.lua"], "beltsim: unknown command 'runn' (did you mean 'run'?) (commands: run,"),
                           (["run", "x.lua", "--tend", "1"], "run does not take: --tend 1 (did you mean '--t-end'?)"),
                           (["run", "x.lua", "--no-frame"], "run does not take: --no-frame (did you mean '--no-frames'?)"),
                           (["wp", "x.lua", "--rtol=1e-3"], "wp does not take: --rtol=1e-3 (did you mean '--rtols'?)"),
                           (["run", "x.lua", "--zzz"], "run does not take: --zzz\n"),
                           # modes' operating point is --at: a --t-end beside it would be a second name for it
                           (["modes", "x.lua", "--t-end", "1"], "modes does not take: --t-end 1")]:
            code, out, err = run(args, cwd=self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn(what, err)

    def test_an_option_given_twice_or_a_word_for_a_count(self):
        # CLI11's own "--t-end: At Most 1 required but received 2"; a word for a whole number was
        # said to need "a finite decimal number"
        for args, what in [(["run", "x.lua", "--t-end", "0.05", "--t-end", "0.1"], "beltsim: --t-end given twice: give it once\n"),
                           (["run", "x.lua", "--rtol", "1e-3", "--rtol", "1e-4", "--rtol", "1e-5"],
                            "beltsim: --rtol given 3 times: give it once\n"),
                           (["sweep", "x.lua", "--jobs", "two"], "beltsim: --jobs must be a whole number >= 1, got two\n"),
                           (["sweep", "x.lua", "--point", "1.5"], "beltsim: --point must be a whole number >= 0, got 1.5\n")]:
            code, out, err = run(args, cwd=self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn(what, err)

    def test_a_flag_takes_no_value(self):
        # CLI11 read a flag's value as a boolean: --check=banana got its raw "Could not convert:
        # --check = banana", and --trusted=2 turned the sandbox off without a word (a user's trial)
        for args in [["run", "x.lua", "--check=banana"], ["run", "x.lua", "--trusted=2"],
                     ["run", "x.lua", "--trusted=false"], ["console", "--no-frames=1"],
                     ["sweep", "x.lua", "--list=no"], ["modes", "x.lua", "--video=true"],
                     ["compare", "a.csv", "b.csv", "--failing=yes"]]:
            flag, value = args[-1].split("=")
            code, out, err = run(args, cwd=self.dir)
            self.assertEqual(code, 2, err)
            self.assertEqual(err, "beltsim: %s takes no value (got '%s=%s'): give %s alone to turn it on, or leave it "
                                  "out\nRun 'beltsim %s --help' for the usage.\n" % (flag, flag, value, flag, args[0]))
            self.assertEqual(os.listdir(self.dir), [], "a refused command wrote")

    def test_sweep_jobs_outside_a_run_of_the_points_is_refused(self):
        # --jobs was ignored by --point, --list, --collect and --slurm: a user who asked for 2 at
        # once learnt nothing
        for form, what in [(["--point", "0"], "--point runs one point, --list and --collect run none"),
                           (["--list"], "--point runs one point"), (["--collect"], "--point runs one point"),
                           (["--slurm"], "with --slurm, --max-parallel bounds the tasks running at once")]:
            code, out, err = run(["sweep", "x.lua", "--jobs", "2"] + form, cwd=self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn("beltsim: --jobs goes with running the points on this machine", err)
            self.assertIn(what, err)
            self.assertEqual(os.listdir(self.dir), [], "a refused sweep wrote")

    def test_an_error_in_a_callback_names_its_line_with_a_traceback(self):
        path = self.script(SCENE + "local function check(s)\n  error('too fast')\nend\n"
                           "sim:every(0.001, function(s) check(s) end)\nsim:run_to(0.003)\n")
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 1, err)
        # the message names the callback and the simulated time, the traceback is where it failed
        self.assertIn("beltsim: %s:14: sim:run_to: sim:every's function (function at %s:13) at t = 0.001 s: %s:11: "
                      "too fast\nstack traceback:\n" % (path, path, path), err)
        self.assertIn("%s:11: in upvalue 'check'" % path, err)
        self.assertIn("%s:13: in function <%s:13>" % (path, path), err)  # the callback
        self.assertIn("%s:14: in main chunk" % path, err)                 # its run_to

    def test_an_input_error_at_the_top_level_has_no_traceback(self):
        # its file:line says it all; "[C]: in field 'scene'" and "in main chunk" below it were noise
        path = self.script("beltsim.scene {\n  pulleys = {},\n  belt = { pretenson = 300 },\n}\n")
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("%s:3: unknown key 'pretenson' in belt (did you mean 'pretension'?)" % path, err)
        self.assertNotIn("traceback", err)

    def test_close_inside_a_callback_is_refused_with_its_line(self):
        path = self.script(SCENE + "sim:every(0.001, function(s) s:close() end)\nsim:run_to(0.003)\n")
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("%s:10: sim:close: this simulation is running" % path, err)
        self.assertNotIn("nil value", err)

    def test_run_and_console_report_a_script_alike(self):
        # the console's once came without the "beltsim: " of every other message of the program
        bad = self.script("error('boom')\n", "bad.lua")
        for script, what in [("missing.lua", "beltsim: cannot open missing.lua: No such file or directory\n"),
                             (bad, "beltsim: " + bad + ":1: boom\n")]:
            for command in ("run", "console"):
                code, out, err = run([command, script], stdin="", cwd=self.dir)
                self.assertEqual(code, 1, command + ": " + err)
                self.assertTrue(err.startswith(what), command + ": " + err)
        code, out, err = run(["console"], stdin="for i = 1, 2 do\n", cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("beltsim: stdin: unfinished input at the end: for i = 1, 2 do\n", err)

    def test_a_missing_input_is_exit_1_in_every_command_but_compare(self):
        # docs/cli.md's rule, as run's for a missing script; compare's 1 means the files differ, so
        # a file it cannot read is its 2 (plot, summary and render were 1 and compare 2 with no rule
        # written)
        for args, what in [(["run", "missing.lua"], "cannot open missing.lua"),
                           (["console", "missing.lua"], "cannot open missing.lua"),
                           (["wp", "missing.lua"], "cannot open missing.lua"),
                           (["modes", "missing.lua"], "cannot open missing.lua"),
                           (["sweep", "missing.lua"], "cannot open missing.lua"),
                           (["plot", "missing.csv"], "cannot read missing.csv"),
                           (["plot", "missing.csv", "--from", "1"], "cannot read missing.csv"),
                           (["summary", "missing"], "cannot read missing/timeseries.csv"),
                           (["summary", "missing/timeseries.csv"], "cannot read missing/timeseries.csv: No such"),
                           (["render", "missing.ckpt", "--out", "x.png"], "missing.ckpt: cannot read it"),
                           (["compare", "missing.csv", "missing.csv"], "cannot read missing.csv")]:
            code, out, err = run(args, stdin="", cwd=self.dir)
            self.assertEqual(code, 2 if args[0] == "compare" else 1, "%s: %s" % (args, err))
            self.assertIn(what, err, args)
        self.assertEqual(os.listdir(self.dir), [])
        code, out, err = run(["--help"])
        self.assertEqual(code, 0, err)
        self.assertIn("an input file that is\nmissing or unreadable (compare: 2)", out)

    def test_a_csv_file_as_the_script(self):
        # trial 16: a run's timeseries.csv given to run got Lua's parse error alone
        path = self.script("t,driver.omega\n0,0\n0.001,1\n", name="timeseries.csv")
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn(path + ": not a Lua script? (its name ends in '.csv', not .lua; a run's CSV files are read by "
                      "beltsim summary and beltsim plot); Lua's parser: " + path + ":2:", err)
        # a script named .lua keeps Lua's message alone
        path = self.script("x = = 1\n", name="bad.lua")
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertNotIn("not a Lua script", err)
        self.assertIn(path + ":1:", err)

    def test_a_folder_as_the_script(self):
        os.mkdir(os.path.join(self.dir, "scenario.lua"))
        for cmd in ["run", "wp"]:
            code, out, err = run([cmd, "scenario.lua"], cwd=self.dir)
            self.assertEqual(code, 1, err)
            self.assertIn("scenario.lua: is a folder, not a script", err)
            self.assertNotIn("empty", err)

    def test_a_tolerance_below_what_double_precision_honours(self):
        path = self.script("print('ran')\n")
        for args, what in [(["run", path, "--rtol", "1e-15"], "--rtol must be in [1e-12, 1) (got 1e-15): double precision cannot honour"),
                           (["wp", path, "--rtols", "1e-3,1e-13"], "--rtols: each must be in [1e-12, 1) (got 1e-13)"),
                           (["wp", path, "--ref-rtol", "1e-14"], "--ref-rtol must be in [1e-12, 1) (got 1e-14)")]:
            code, out, err = run(args, cwd=self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn(what, err)
            self.assertNotIn("ran", out)

    def test_wp_names_its_reference_and_takes_another(self):
        # trbdf2 by default (sim/work_precision.hpp); --ref-integrator another, an unknown one refused
        path = self.script(two_pulley(elements=30) + 'drive:run { t_end = 0.005, progress = false }\n')
        for extra, reference in [([], "reference:trbdf2"), (["--ref-integrator", "esdirk32"], "reference:esdirk32")]:
            out_dir = os.path.join(self.dir, "wp" + str(len(extra)))
            code, out, err = run(["wp", path, "--integrators", "trbdf2", "--rtols", "1e-2", "--ref-rtol", "1e-4",
                                  "--out", out_dir] + extra, cwd=self.dir)
            self.assertEqual(code, 0, err)
            with open(os.path.join(out_dir, "wp.csv")) as f:
                names = [line.split(",")[0] for line in f.read().splitlines()[1:]]
            self.assertIn(reference, names)
        code, out, err = run(["wp", path, "--ref-integrator", "bogus"], cwd=self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("unknown integrator 'bogus' (valid: esdirk32, trbdf2", err)
        # a slip of the finger is named as every other misspelt name is
        code, out, err = run(["wp", path, "--ref-integrator", "trbdf"], cwd=self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("unknown integrator 'trbdf' (did you mean 'trbdf2'?) (valid: esdirk32", err)

    def test_wp_refuses_a_live_simulation_at_once(self):
        # trial 12: wp on a script that runs scene:start ran the whole simulation (into out/<script>,
        # whatever --out), then said "the script never calls scene:run{}", without file:line
        text = SCENE.replace('out = "out"', 'out = "live"') + "sim:run_to(0.05)\nsim:close()\n"
        path = self.script(text, "live.lua")
        line = text.splitlines().index('local sim = drive:start { progress = false, out = "live" }') + 1
        for command in ["wp", "modes"]:
            out_dir = os.path.join(self.dir, command + "_out")
            code, out, err = run([command, path, "--out", out_dir], cwd=self.dir)
            self.assertEqual(code, 1, err)
            self.assertIn("%s:%d: scene:start: beltsim %s takes the scene and settings of a batch run, scene:run{}, "
                          "and this script runs a live simulation here; nothing was run. To measure it, write its "
                          "run as scene:run{ t_end = ..., events = {...} }" % (path, line, command), err)
            self.assertNotIn("never calls scene:run", err)
            for folder in ["live", out_dir, os.path.join(self.dir, "out")]:
                self.assertFalse(os.path.exists(folder), command + ": " + folder)

    def test_check_estimates_the_error_of_each_run(self):
        # --check: each run ends with its estimate, written to parameters.csv (sim/run_check.hpp)
        path = self.script(two_pulley(elements=30) + 'drive:run { t_end = 0.01, progress = false, out = "out" }\n')
        params = os.path.join(self.dir, "out", "parameters.csv")
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertNotIn("check:", err)
        with open(params) as f:
            self.assertIn("\nrun.check,0,,run,", f.read())
        code, out, err = run(["run", path, "--check", "--rtol", "1e-2"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        # (a warning when past 3×rtol in the speeds: the first 10 ms of this coarse belt at 1e-2 are, 0.6 of the speeds)
        self.assertRegex(err, "beltsim: (warning: )?check: estimated error of the pulley speeds ")
        self.assertIn("(relative to their largest values over the run; rtol 0.01, companion at 0.001)", err)
        with open(params) as f:
            text = f.read()
        self.assertIn("\nrun.check,1,,run,", text)
        self.assertIn("\ncheck.err_speed,", text)
        self.assertIn("\ncheck.err_tension,", text)

    def test_check_says_when_its_estimate_may_be_low(self):
        # the companion at a tenth of the tolerance takes 2-4 times the run's steps where the
        # tolerance sets them (the dry drive: 3.9 at rtol 1e-3), about as many where something
        # else does (the half-wet drive's first 50 ms under Stribeck's law at rtol 1e-2, whose
        # steps follow the falling curve's growth: 1.01; docs/accuracy.md), and then the
        # closing line warns
        scripts = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")
        for script, sets, t_end, rtol, shared in [("paper_wet.lua", ["--set", "friction=stribeck"], "0.05", "1e-2", True),
                                                  ("paper_dry.lua", [], "0.1", "1e-3", False)]:
            out_dir = os.path.join(self.dir, script)
            code, out, err = run(["run", os.path.join(scripts, script)] + sets +
                                 ["--t-end", t_end, "--rtol", rtol, "--check", "--no-frames", "--out", out_dir],
                                 cwd=self.dir)
            self.assertEqual(code, 0, err)
            with open(os.path.join(out_dir, "parameters.csv")) as f:
                rows = dict(line.split(",", 2)[:2] for line in f.read().splitlines() if line.startswith("check."))
            ratio = float(rows["check.steps_ratio"])
            if shared:
                self.assertLess(ratio, 1.3, script)
                self.assertEqual(rows["check.shared"], "1")
                self.assertRegex(err, r"beltsim: warning: check: .*; the companion took only [0-9.]+ times the "
                                 r"run's steps .* the estimate may be low")
            else:
                self.assertGreater(ratio, 2, script)
                self.assertEqual(rows["check.shared"], "0")
                self.assertNotIn("may be low", err)

    def test_a_set_key_that_is_a_reserved_word(self):
        path = self.script("print(beltsim.args['and'])\n")
        for key in ["and", "end", "nil", "goto"]:
            code, out, err = run(["run", path, "--set", key + "=5"], cwd=self.dir)
            self.assertEqual(code, 2, key + ": " + err)
            self.assertIn("--set %s=5: the key must be a Lua name, and '%s' is one of Lua's reserved words" % (key, key),
                          err)

    def test_environment_variables_with_unknown_values(self):
        path = self.script("print('ran')\n")
        for var, value, words in [("BELTSIM_GL", "vulkan", "osmesa, egl\n"),
                                  ("BELTSIM_TERM_IMAGES", "ascii-art", "off, symbols, sixel, kitty, iterm\n"),
                                  ("BELTSIM_GL", "elg", "osmesa, egl (did you mean 'egl'?)"),
                                  ("BELTSIM_TERM_IMAGES", "sixle", "off, symbols, sixel, kitty, iterm (did you mean 'sixel'?)")]:
            p = subprocess.run([BELTSIM, "run", path], capture_output=True, text=True, cwd=self.dir, timeout=60,
                               env=dict(os.environ, **{var: value}))
            self.assertEqual(p.returncode, 2, p.stderr)
            self.assertIn("beltsim: %s=%s is not one of %s" % (var, value, words), p.stderr)
            self.assertNotIn("ran", p.stdout)

    def test_an_empty_out_is_refused(self):
        # '--out ""' (an unset shell variable) would be the folder beltsim runs in, silently
        path = self.script(two_pulley(elements=30) + 'drive:run { t_end = 0.002, progress = false }\n')
        csv = os.path.join(self.dir, "t.csv")
        with open(csv, "w") as f:
            f.write("t,x\n0,1\n")
        for args in [["run", path], ["wp", path], ["console"], ["sweep", path], ["plot", csv], ["render", csv]]:
            code, out, err = run(args + ["--out", ""], cwd=self.dir)
            self.assertEqual(code, 2, "%s: %s" % (args[0], err))
            self.assertIn("beltsim: --out: an empty path (leave --out out for its default, or give '.' for the "
                          "folder beltsim runs in)\nRun 'beltsim %s --help' for the usage." % args[0], err)
            self.assertEqual(sorted(os.listdir(self.dir)), ["s.lua", "t.csv"], args[0])
        # a run's out = "" in a script the same
        path = self.script(two_pulley(elements=30) + 'drive:run { t_end = 0.002, progress = false, out = "" }\n')
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("s.lua:9: run.out: an empty path (leave it out for out/<script>, or give '.' for the folder "
                      "beltsim runs in)", err)
        self.assertEqual(sorted(os.listdir(self.dir)), ["s.lua", "t.csv"])

    def test_a_second_run_into_a_folder_says_it_replaces_the_first(self):
        # the console's scenario ran into out/s, and a simulation started at the prompt without an
        # out replaced its outputs without a word: each later run into a folder of an earlier one says so
        # (a run refused before its outputs opened uses no folder: a retry into it is no replacement)
        path = self.script(two_pulley(elements=30) +
                           'pcall(drive.run, drive, { t_end = 0.002, progress = false, snapshots = { times = {5} } })\n'
                           'drive:run { t_end = 0.002, progress = false }\n'
                           'drive:run { t_end = 0.002, progress = false, out = "other" }\n'
                           'local sim = drive:start { progress = false, out = "out/s/" }\n'
                           'sim:close()\n')
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(err.count("holds the outputs of an earlier run of this command"), 1, err)
        self.assertIn("beltsim: warning: start: the output folder out/s/ holds the outputs of an earlier run of this "
                      "command, which this one replaces (give each run its own folder: out = ..., or --out)", err)
        # --out puts every run into one folder: the advice is to leave it out
        code, out, err = run(["run", path, "--out", "o"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(err.count("holds the outputs of an earlier run of this command"), 2, err)
        self.assertIn("(--out puts every run of the script into that one folder: leave it out and give each run its "
                      "own out = ...)", err)

    def test_a_run_into_a_folder_in_use_is_refused_without_the_replacement_warning(self):
        # a second scene:start{} into the folder of a live simulation said first that it replaced
        # the earlier run's outputs, then was refused: the refusal comes alone
        path = self.script(two_pulley(elements=30) +
                           'local a = drive:start { progress = false, out = "o" }\n'
                           'local ok, e = pcall(drive.start, drive, { progress = false, out = "o" })\n'
                           'print(e)\n'
                           'a:close()\n')
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("start: the output folder o is in use by another simulation of this beltsim", out)
        self.assertNotIn("which this one replaces", err)


if __name__ == "__main__":
    BELTSIM = sys.argv.pop(1)
    unittest.main(verbosity=2)
