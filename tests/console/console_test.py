#!/usr/bin/env python3
"""Tests of `beltsim console` (src/script/console.cpp): the interactive Lua prompt driven through a
pseudo-terminal (readline: prompts, multi-line chunks, completion, history, Ctrl-C, Ctrl-D) and the
piped mode (no prompt, exit status, session.lua and its replay with `beltsim run`).

Usage: console_test.py PATH/TO/beltsim [unittest options]

Each test works in its own temporary folder (the console's working directory), with BELTSIM_HISTORY
pointing into it and the test scene (support/two_pulley.lua, 40 elements) that starts a live simulation `sim`
writing into arg[1] (after `--`) or <tmp>/out. Nothing sleeps blindly: every wait has a deadline and
a failure shows the terminal transcript.
"""

import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import termios
import time
import unittest

from pty_console import PROMPT, STARTUP_TIMEOUT, TIMEOUT, Console, child_env  # tests/console/pty_console.py

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None  # set from argv in main

# the test scene (tests/support/two_pulley.lua), started live
SCENARIO = two_pulley(40) + 'sim = drive:start{ out = arg and arg[1] or "%(out)s" }\n'


class ConsoleTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="beltsim_console_")
        self.addCleanup(shutil.rmtree, self.tmp, True)
        with open(os.path.join(self.tmp, "scenario.lua"), "w") as f:
            f.write(SCENARIO % {"out": os.path.join(self.tmp, "out").replace("\\", "/")})
        self.consoles = []

    def tearDown(self):
        for c in self.consoles:
            c.kill()

    def console(self, args=()):
        c = Console(BELTSIM, self, self.tmp, args)
        self.consoles.append(c)
        return c

    def piped(self, commands, args=(), timeout=60, flags=()):
        argv = [BELTSIM, "console", "scenario.lua"] + list(flags) + (["--"] + list(args) if args else [])
        return subprocess.run(argv, input="".join(c + "\n" for c in commands).encode(), cwd=self.tmp,
                              env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              timeout=timeout)

    # 1
    def test_banner_and_expressions(self):
        c = self.console()
        banner = c.screen
        self.assertIn("help()", banner, c.transcript())
        self.assertIn("Ctrl-D", banner, c.transcript())
        # the script's globals are named (its local drive is not one)
        self.assertIn("globals from scenario.lua: sim\n", banner, c.transcript())
        out = c.command("6*7")
        self.assertRegex(out, r"\n42\n", c.transcript())
        out = c.command("return 6*7")
        self.assertRegex(out, r"\n42\n", c.transcript())

    # 2
    def test_multi_line_chunk(self):
        c = self.console()
        c.command("for i = 1, 3 do", continuation=True)
        c.command("print(i*10)", continuation=True)
        out = c.command("end")
        self.assertRegex(out, r"\n10\n20\n30\n", c.transcript())

    # 3
    def test_error_then_good_command(self):
        c = self.console()
        out = c.command("nosuch()")
        self.assertIn("stdin:1:", out, c.transcript())
        self.assertIn("attempt to call a nil value", out, c.transcript())
        out = c.command("1+1")
        self.assertRegex(out, r"\n2\n", c.transcript())

    # 4
    def test_completion_of_a_method(self):
        c = self.console()
        mark = c.complete("sim:adv", "sim:advance(", "the completion of sim:adv to sim:advance(")
        c.send("0.001)\r")
        c.wait_prompt(mark)
        out = c.screen[mark:]
        self.assertIn("sim:advance(0.001)", out, c.transcript())
        self.assertRegex(out, r"\n\s*t = 0\.001,", c.transcript())
        self.assertRegex(out, r"interrupted = false", c.transcript())

    # 5
    # the history file does not exist before the first session (readline's append_history does
    # not create it: the console must)
    def test_history_recalled_by_a_new_console(self):
        hist = os.path.join(self.tmp, "history")
        c = self.console()
        c.command("x = 5")
        self.assertEqual(c.eof(), 0, c.transcript())
        self.assertTrue(os.path.exists(hist), "no history file %s after the session%s" % (hist, c.transcript()))
        with open(hist) as f:
            self.assertIn("x = 5", f.read().splitlines())
        c = self.console()
        mark = len(c.screen)
        c.send("\x1b[A")
        c.wait_for("x = 5", what="the recalled line 'x = 5'", start=mark)
        c.send("\r")
        c.wait_prompt(mark)
        out = c.command("x")
        self.assertRegex(out, r"\n5\n", c.transcript())

    # 6
    def test_ctrl_c_clears_the_line(self):
        c = self.console()
        mark = len(c.screen)
        c.send("nosuch_var_xyz")
        c.wait_for("nosuch_var_xyz", start=mark)
        # ^C right after the echo: it may come while readline is still busy echoing; the console
        # must not lose it (it once did, in 2 of 12 runs, when only a failed read() noticed it)
        mark = len(c.screen)
        c.send("\x03")
        c.wait_prompt(mark)
        out = c.command("1+2")
        after = c.screen[mark:]
        self.assertRegex(out, r"\n3\n", c.transcript())
        self.assertNotIn("nosuch_var_xyz", after, c.transcript())
        self.assertNotIn("attempt to", after, c.transcript())
        self.assertNotIn("nil", after, c.transcript())

    # 7
    def test_ctrl_c_stops_a_run(self):
        c = self.console()
        mark = len(c.screen)
        c.send("r = sim:advance(10)\r")
        # ^C once the run is under way, seen in its output (0.1 s simulated: 100 rows of 1 ms), not
        # after a wait of wall time, which a loaded machine may spend on the scene's build
        csv = os.path.join(self.tmp, "out", "timeseries.csv")

        def rows():
            try:
                with open(csv) as f:
                    return f.read().count("\n")
            except FileNotFoundError:
                return 0

        deadline = time.monotonic() + TIMEOUT
        while rows() <= 100:
            self.assertLess(time.monotonic(), deadline, "no 100 rows of the run in %g s" % TIMEOUT + c.transcript())
            if not c.pump(0.02):
                self.fail("the console ended during the run" + c.transcript())
        self.assertIsNone(PROMPT.search(c.screen, mark), "the 10 s run ended before ^C" + c.transcript())
        c.send("\x03")
        c.wait_prompt(mark, timeout=5)
        out = c.command("r.interrupted")
        self.assertRegex(out, r"\ntrue\n", c.transcript())
        out = c.command("sim.t")
        m = re.search(r"\n([0-9.eE+-]+)\n", out)
        self.assertTrue(m, "sim.t printed no number" + c.transcript())
        t = float(m.group(1))
        self.assertGreater(t, 0)
        self.assertLess(t, 10)
        with open(os.path.join(self.tmp, "out", "timeseries.csv")) as f:
            text = f.read()
        lines = text.split("\n")
        self.assertEqual(lines[-1], "", "timeseries.csv does not end with a line end: %r" % text[-300:])
        header, last = lines[0], lines[-2]
        self.assertGreater(len(lines), 3, text[-300:])
        self.assertEqual(last.count(","), header.count(","), "incomplete last row %r" % last)
        self.assertLessEqual(float(last.split(",")[0]), t + 1e-12)
        # the replay stops where the run stopped and keeps its result in r, as the session did
        self.assertEqual(c.eof(), 0, c.transcript())
        with open(os.path.join(self.tmp, "out", "scenario", "session.lua")) as f:
            lines = f.read().splitlines()
        self.assertIn("-- r = sim:advance(10)  -- stopped by Ctrl-C", lines)
        kept = [ln for ln in lines if ln.startswith("r = sim:run_to(")]
        self.assertEqual(len(kept), 1, lines)
        # (the console prints sim.t to 10 significant digits)
        self.assertAlmostEqual(float(kept[0][len("r = sim:run_to("):-1]) / t, 1, delta=1e-9, msg=lines)

    # 7b
    def test_keys_typed_during_a_run_wait_for_the_next_prompt(self):
        # a user typed while a run's progress line showed: the keys were echoed onto it ("...
        # 57997 stepsbcllo there"). The terminal's echo is off while the line shows; what was typed
        # is the next prompt's, to edit or run; a Ctrl-C (here in the run's callback) drops it (the
        # terminal discards its input on Ctrl-C), and the echo is back after every run
        c = self.console()
        c.command("function slow() local c = os.clock() while os.clock() - c < 0.02 do end end")
        c.command("id = sim:every(0.001, slow)")
        for stop in [False, True]:
            mark = len(c.screen)
            c.send("r = sim:advance(%s)\r" % ("10" if stop else "0.15"))
            c.wait_for(re.compile(r"beltsim: t = [^\n]*steps"), what="the progress line", start=mark)
            self.assertFalse(termios.tcgetattr(c.fd)[3] & termios.ECHO, "the terminal echoes during the run" +
                             c.transcript())
            c.send("typed ahead")
            if stop:
                time.sleep(0.5)  # what was typed reaches the terminal's input before Ctrl-C
                c.send("\x03")
            if stop:
                c.wait_prompt(mark, timeout=60)  # an empty prompt: dropped with the run
            else:
                c.wait_for(re.compile(r"\n> typed ahead$"), 60, "the keys at the next prompt", mark)
            shown = c.screen[mark:]
            before = shown[:shown.rfind("\n> ")]  # the run, its progress and its result
            self.assertNotIn("typed", before, c.transcript())
            if not stop:
                c.send("\x15")  # readline's Ctrl-U: the line is emptied
                out = c.command("r.t")
                self.assertRegex(out, r"\n0\.15\n", c.transcript())
        self.assertEqual(c.eof(), 0, c.transcript())
        self.assertTrue(c.echoed_at_end, "the console left the terminal without echo")

    # 8
    def test_ctrl_d_writes_session_lua(self):
        c = self.console()
        c.command("y = 2")
        c.command("nosuch()")
        c.command("sim:advance(0.001)")
        self.assertEqual(c.eof(), 0, c.transcript())
        m = re.search(r"the session's commands are in (\S+)", c.screen)
        self.assertTrue(m, "where session.lua went is not said" + c.transcript())
        path = os.path.join(self.tmp, m.group(1))
        self.assertTrue(path.endswith("session.lua"), path)
        self.assertTrue(os.path.isfile(path), path)
        with open(path) as f:
            lines = f.read().splitlines()
        self.assertIn("y = 2", lines)
        self.assertIn("sim:advance(0.001)", lines)
        self.assertLess(lines.index("y = 2"), lines.index("sim:advance(0.001)"))
        # a command that failed is replayed under pcall (it may have changed something first)
        at = lines.index("nosuch()")
        self.assertEqual(lines[at - 2:at + 2], ["-- failed at the prompt: stdin:1: attempt to call a nil value (global "
                                                "'nosuch')", "pcall(function()", "nosuch()", "end)"])

    # 8b
    def test_sighup_closes_like_sigterm(self):
        # the terminal going away (SIGHUP): the outputs are closed, session.lua is written, 129
        c = self.console()
        c.command("y = 2")
        os.kill(c.pid, signal.SIGHUP)
        deadline = time.monotonic() + TIMEOUT
        while c.pump(deadline - time.monotonic()) and time.monotonic() < deadline:
            pass
        status = c._reap(deadline)
        self.assertEqual(status, 129, c.transcript())
        with open(os.path.join(self.tmp, "out", "scenario", "session.lua")) as f:
            self.assertIn("y = 2", f.read().splitlines())

    # 9
    def test_pipe_mode(self):
        r = self.piped(["sim:advance(0.002)", "print(sim.t)"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertNotIn("> ", out)
        self.assertNotIn("\x1b", out)
        self.assertRegex(out, r"t = 0\.002,")
        self.assertIn("\n0.002\n", out)
        r = self.piped(['error("boom")', 'print("after " .. "boom")'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertIn("boom", err)
        self.assertIn("after boom\n", out, err)
        self.assertEqual(r.returncode, 1, out + err)

    def test_a_checked_runs_estimate_prints_without_a_force_unit(self):
        # the check's tension is a relative error (io/units.cpp kRunResult), not a span's tension
        # in N: printed, its fields carry the run result's units (none; a time's s), and no N
        r = self.piped(["sim:advance(0.002)", "s = sim:stats()", "s.check", "s"], flags=["--check"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertRegex(out, r"\n  limit_tension = [0-9.e-]+,\n")
        self.assertRegex(out, r"\n  tension = [0-9.e-]+,\n")
        self.assertRegex(out, r"\n    tension = [0-9.e-]+,\n")  # the stats' own check table, nested
        self.assertNotRegex(out, r"tension = [0-9.e-]+, -- N")
        self.assertRegex(out, r"\n  wall = [0-9.e-]+, -- s\n")  # a field's unit elsewhere as before

    def test_tables_with_two_table_fields_print(self):
        # a table with two or more table fields, the API's results among them (the printer popped
        # a value too many after the first: "printing the result: attempt to index a nil value"),
        # and the session replays them
        commands = ["{a = {}, b = {}}", "beltsim.print({a = {k = 1}, b = {k = 2}, c = 3})", "sim:advance(0.01)",
                    "s = sim:summary{}", "s", "s.spans", "s.hubs", "sim:summary{}", "m = sim:modes{}", "m", "m[1]",
                    "'the end'"]
        r = self.piped(commands, args=[os.path.join(self.tmp, "out_console")])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertNotIn("printing the result", err)
        self.assertTrue(out.startswith("{\n  a = {},\n  b = {},\n}\n{\n  a = { k = 1 },\n  b = { k = 2 },\n  c = 3,\n}\n"),
                        out)
        self.assertRegex(out, r"\n  spans = \{\n    span_driven_driver = \{\s+tension_max = ")
        self.assertRegex(out, r"\n\{\n  span_driven_driver = \{\s+tension_max = ")  # s.spans
        self.assertRegex(out, r"\n\{\n  driven = \{\s+hub_load_max = ")  # s.hubs
        self.assertEqual(len(re.findall(r"\n  hubs = \{\n", out)), 2, out)  # s and sim:summary{}
        self.assertRegex(out, r"\n  \{\n    damping = ")  # m, its modes a list
        self.assertRegex(out, r"\n\{\n  damping = [^\n]*\n  decay = [^\n]*\n  frequency = [^\n]*\n  share = \{")
        self.assertTrue(out.endswith('"the end"\n'), out)
        # the summary's table text, several lines, prints as its lines in a long string (a trial read
        # it as one escaped line), the rest of the strings quoted
        self.assertRegex(out, r"\n  table = \[\[\nsummary of [^\n]*\n\nspans ")
        self.assertNotIn("\\n", out)
        m = re.search(r"the session's commands are in (\S+)", err)
        self.assertTrue(m, err)
        r = subprocess.run([BELTSIM, "run", "--trusted", os.path.join(self.tmp, m.group(1))], cwd=self.tmp,
                           env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode())
        self.assertTrue(r.stdout.decode().endswith('"the end"\n'), r.stdout.decode())

    def test_units_are_the_results_own(self):
        # a number prints the unit its result recorded (the summary's figures, sim:pulley's fields
        # from io/units.cpp), not one guessed from its key's name: the summary's losses are powers
        # in W (they printed J and N), tension_min N as tension_mean, the hubs' loads N (none); a
        # table of the user's own prints no unit (its y printed m)
        with open(os.path.join(self.tmp, "scenario.lua"), "w") as f:
            f.write((SCENARIO % {"out": os.path.join(self.tmp, "out").replace("\\", "/")})
                    .replace("direction = 'cw' },", "direction = 'cw' },\n  energy = true,", 1))
        r = self.piped(["sim:advance(0.01)", "s = sim:summary{}", "s.loss", "s.spans", "s.hubs",
                        "{x = {y = 1}, driver = {tension_mean = 1, tension_min = 2}}", 'sim:pulley("driven")'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        blocks = re.findall(r"(?ms)^\{\n.*?^\}\n", out)
        self.assertEqual(len(blocks), 6, out)
        loss, spans, hubs, mine, pulley = blocks[1:]
        for q in ["axial", "bending", "contact", "friction", "total", "input", "output", "stored"]:
            self.assertRegex(loss, r"\n  %s = [-0-9.e]+, -- W\n" % q, loss)
        self.assertRegex(loss, r"\n  share = [-0-9.e]+,\n", loss)
        for q in ["tension_mean", "tension_min", "tension_max"]:
            self.assertRegex(spans, r"\n    %s = [-0-9.e]+, -- N\n" % q, spans)
        for q in ["hub_load_mean", "hub_load_max", "hub_load_spans"]:
            self.assertRegex(hubs, r"\n    %s = [-0-9.e]+, -- N\n" % q, hubs)
        self.assertNotIn("--", mine)
        self.assertRegex(pulley, r"\n  omega = [-0-9.e]+, -- rad/s\n  slip_arc = [-0-9.e]+, -- m\n", pulley)
        self.assertRegex(pulley, r"\n  mu = 1,\n", pulley)

    def test_a_local_of_an_earlier_line_is_named_when_its_nil_fails(self):
        # each prompt line is a chunk of its own: its locals end with it (lua-api.md's every/when
        # example pasted line by line failed with "got nil" and no word why)
        r = self.piped(["local target, dt = -30, 0.002", "sim:every(dt, function(sim) end)",
                        "sim:every(nosuch, function(sim) end)", "local function g() return 1 end", "g()"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 1, out + err)
        self.assertIn("stdin:1: sim:every(dt, fn): argument 1 (dt): number expected, got nil\nnote: dt was declared "
                      "`local` on an earlier line, and a local at the prompt lasts for its own line only: declare it "
                      "without `local` to keep it\n", err)
        self.assertEqual(err.count("note: "), 2, err)  # not for nosuch, which no line declared
        self.assertIn("note: g was declared `local`", err)

    def test_an_error_shows_a_traceback_from_inside_a_function(self):
        # console.md: a command's own error (an API call's among them) is its stdin:N: line; one
        # raised inside a function adds the calls that led there
        r = self.piped(["sim:run_to(-1)", "function f()", "  sim:run_to(-1)", "end", "f()"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 1, out + err)
        self.assertIn("\nstdin:1: sim:run_to: -1 s is before now (0 s)\nstdin:2: sim:run_to: -1 s is before now (0 s)\n"
                      "stack traceback:\n\t[C]: in method 'run_to'\n\tstdin:2: in function 'f'\n", err)

    def test_a_speed_set_past_a_belts_rating_is_warned_of(self):
        # as the scene build warns of a scene's speeds (scene/scene.hpp kBeltSpeedWarn, 60 m/s)
        r = self.piped(['sim:set_speed("driver", 10)', 'sim:set_speed("driver", beltsim.ramp(0.1, 5000))'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertEqual(len(re.findall(r"warning: sim:set_speed", err)), 1, err)
        self.assertRegex(err, r"warning: sim:set_speed: pulley 'driver'\.speed: 5000 rad/s once its ramps and tables "
                         r"have ended, which moves the belt at [0-9.]+ m/s .*beltsim\.rpm\(5000\)")

    def test_a_speed_the_other_way_round_is_warned_of(self):
        # a trial set +50 rad/s on a pulley turning at -45 (a sign mistake) without a word; a start
        # from rest and a change within one sense are not warned of
        r = self.piped(['sim:set_speed("driver", -10)', 'sim:set_speed("driver", -20)',
                        'sim:set_speed("driver", 15)'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertEqual(len(re.findall(r"warning: sim:set_speed", err)), 1, err)
        self.assertIn("warning: sim:set_speed: driver turned at -20 rad/s and now at 15 rad/s: it reverses at once, "
                      "and the belt with it (a pulley's speed is positive counter-clockwise)", err)

    def test_a_law_whose_changes_all_lie_before_now_is_warned_of(self):
        # law times are absolute: a ramp typed at t = 0.02 s as if from now (a user's trial) jumps
        # to its end at once; a law with a change still ahead is not warned of
        r = self.piped(['sim:run_to(0.02)', 'sim:set_speed("driver", beltsim.ramp(0.01, -10))',
                        'sim:set_torque("driven", beltsim.step{t = 0.05, from = -5, to = -10})',
                        'sim:set_torque("driven", -5)'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertEqual(len(re.findall(r"warning: sim:set_", err)), 1, err)
        self.assertIn("warning: sim:set_speed: every change of this law in time lies before now (its last at "
                      "t = 0.01 s, now t = 0.02 s): driver holds its final value from here, at once", err)

    def test_closing_a_simulation_says_where_it_ended_once(self):
        # sim:close() says the closing line of its runs, as `beltsim run` does; the console's own
        # end (the interpreter's, which closes every simulation) does not say it again
        r = self.piped(["sim:advance(0.002)", "sim:close()", "sim:close()"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertEqual(len(re.findall(r"run ended", err)), 1, err)
        self.assertRegex(err, r"\nbeltsim: run ended at t = 0\.002 s \([0-9]+ steps, [0-9.e-]+ s\): %s/\n"
                         % re.escape(os.path.join(self.tmp, "out")), err)
        # a simulation left open at the end closes as before, without a line
        r = self.piped(["sim:advance(0.002)"])
        self.assertEqual(r.returncode, 0, r.stderr.decode())
        self.assertNotIn("run ended", r.stderr.decode())

    def test_a_study_folder_is_refused_before_the_script_runs(self):
        # session.lua was written among a study's points (out/scenario, a quick sweep's default)
        study = os.path.join(self.tmp, "out", "scenario")
        os.makedirs(study)
        with open(os.path.join(study, "summary.csv"), "w") as f:
            f.write("point,pretension,status\n0,300,ok\n")
        r = self.piped(["print('ran')"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 1, out + err)
        self.assertIn("beltsim: console: the folder out/scenario, where this session's runs and session.lua would "
                      "go, holds a study of `beltsim sweep` (its points vary pretension): give the console a folder "
                      "of its own (--out DIR)", err)
        self.assertNotIn("ran", out)
        self.assertEqual(sorted(os.listdir(study)), ["summary.csv"])
        r = self.piped(["print('ran')"], flags=["--out", "out/mine"])
        self.assertEqual(r.returncode, 0, r.stderr.decode())
        self.assertTrue(os.path.exists(os.path.join(self.tmp, "out", "mine", "session.lua")))

    def test_changes_say_what_they_did(self):
        # wet, set_torque and set_mu return one line: which elements changed (how many, in contact
        # with which pulley now), old -> new; those that already had the μ are not counted (they
        # were: "40 of 40 elements ..., mu 0.5 -> 0.5"); sim:elements{ pulley } lists the elements on
        # a pulley
        r = self.piped(["sim:advance(0.002)", "sim:wet{ mu = 0.2, from = 0, to = 0.3 }",
                        'sim:set_torque("driver", -10)', "sim:set_mu(0.5)", "sim:set_mu(0.5)",
                        "sim:wet{ mu = 0.2, from = 0, to = 0.3 }", "sim:set_mu(0.5)",
                        'sim:elements{ pulley = "driven" }',
                        'print(#sim:elements{ pulley = "driven" } == tonumber(sim:wet{ mu = 0.7 }:match("(%d+) on driven")))'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        # 0.3 m of the 40-element belt's length (2·0.29 + 2π·0.1 m): 10 elements, μ 1 -> 0.2
        self.assertRegex(out, r'"wet: 10 of 40 elements \([^)]*\), mu 1 -> 0\.2"', out)
        self.assertRegex(out, r'"driver: torque \{.*ramp.*\} -> torque -10 from t = 0\.002 s"', out)
        self.assertRegex(out, r'"set_mu: 40 of 40 elements \(\d+ on driver, \d+ on driven, \d+ free\), '
                              r'mu \[0\.2, 1\] -> 0\.5"', out)
        self.assertIn('"set_mu: no element changed (the 40 it sets already had mu 0.5)"', out)
        self.assertRegex(out, r'"set_mu: 10 of 40 elements \([^)]*\), mu 0\.2 -> 0\.5"', out)
        self.assertRegex(out, r"\{\n  \d+,\n", out)
        self.assertIn("\ntrue\n", out)

    # 10
    def test_session_replays(self):
        out_console = os.path.join(self.tmp, "out_console")
        r = self.piped(["sim:advance(0.003)", "sim:wet{from=0.1, to=0.3, mu=0.2}", "sim:advance(0.003)"],
                       args=[out_console])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        m = re.search(r"the session's commands are in (\S+)", err)
        self.assertTrue(m, "where session.lua went is not said: " + err)
        session = os.path.join(self.tmp, m.group(1))
        self.assertTrue(os.path.isfile(session), session)
        with open(os.path.join(out_console, "timeseries.csv"), "rb") as f:
            series = f.read()
        with open(os.path.join(out_console, "events.csv")) as f:
            events = f.read()
        self.assertIn("\n0.003,wet,", events)
        # session.lua sets arg (out_console) itself: the replay writes the same folder, so keep the
        # console's outputs and remove them before replaying
        shutil.move(out_console, out_console + "_kept")
        # the scenario's text is in session.lua: the replay needs neither the file nor its folder
        # (which the sandbox would not let it read)
        os.rename(os.path.join(self.tmp, "scenario.lua"), os.path.join(self.tmp, "scenario_moved.lua"))
        # its runs wrote beside the scenario, outside session.lua's folders: the sandbox refuses
        # that, and --trusted (which session.lua's header names) replays it
        r = subprocess.run([BELTSIM, "run", session], cwd=self.tmp, env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        self.assertEqual(r.returncode, 1, (r.stdout + r.stderr).decode())
        self.assertIn("start.out: writing '%s' is not allowed" % out_console, r.stderr.decode())
        self.assertFalse(os.path.exists(out_console))
        r = subprocess.run([BELTSIM, "run", "--trusted", session], cwd=self.tmp, env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        with open(session) as f:
            text = f.read()
        self.assertIn("needs: beltsim run --trusted", text)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        with open(os.path.join(out_console, "timeseries.csv"), "rb") as f:
            replayed = f.read()
        self.assertGreater(series.count(b"\n"), 3)
        self.assertEqual(replayed, series, "the replay's timeseries.csv differs; session.lua:\n" + text)
        with open(os.path.join(out_console, "events.csv")) as f:
            self.assertIn("\n0.003,wet,", f.read())

    # 10c
    def test_session_replays_a_command_that_failed_after_it_ran(self):
        # an `every` callback raises at t = 0.003 s: the run stops there and the next command goes on
        # from there; the failed command is replayed (under pcall), so the replay reaches the same
        # outputs (it was left out, and the replay ran the first run to its end)
        out_console = os.path.join(self.tmp, "out_console")
        r = self.piped(["n = 0", "sim:every(0.001, function(s) n = n + 1; if n == 3 then error('boom') end end)",
                        "sim:run_to(0.006)", "sim:run_to(0.008)", "print('t', sim.t, 'n', n)"], args=[out_console])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 1, out + err)
        self.assertIn("boom", err)
        self.assertIn("t\t0.008\tn\t8", out)
        session = os.path.join(self.tmp, re.search(r"the session's commands are in (\S+)", err).group(1))
        with open(session) as f:
            text = f.read()
        self.assertIn("-- failed at the prompt: ", text)
        self.assertIn("\npcall(function()\nsim:run_to(0.006)\nend)\n", text)
        with open(os.path.join(out_console, "timeseries.csv"), "rb") as f:
            series = f.read()
        shutil.move(out_console, out_console + "_kept")
        r = subprocess.run([BELTSIM, "run", "--trusted", session], cwd=self.tmp, env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        self.assertIn("t\t0.008\tn\t8", r.stdout.decode())
        with open(os.path.join(out_console, "timeseries.csv"), "rb") as f:
            self.assertEqual(f.read(), series, "the replay's timeseries.csv differs; session.lua:\n" + text)

    # 10d
    def test_a_session_that_resumed_replays_into_its_own_folder(self):
        # trial 22: a session saved a checkpoint, went on, closed and resumed it (rewind = true);
        # its replay resumed the session's checkpoint, so it wrote into the session's folder
        # (parameters.csv rewritten) and its own timeseries.csv stopped at the resume. The
        # replay resumes its own copy (replay/ck/t.ckpt), leaves the session's folder as it was
        # and gives the same timeseries.csv
        with open(os.path.join(self.tmp, "scenario.lua"), "w") as f:  # into out/scenario, the default
            f.write(two_pulley(40) + "sim = drive:start{ progress = false }\n")
        # (and a branch beside the session's folder, out/branch, which the replay redirects into its own:
        # trial 25's replay was refused by its sandbox there, and under --trusted wrote over it)
        r = self.piped(["sim:run_to(0.003)", 'sim:save("ck/t.ckpt")', "sim:wet{from=0.1, to=0.3, mu=0.2}",
                        "sim:run_to(0.005)", "sim:close()",
                        'b = beltsim.resume("out/scenario/ck/t.ckpt", {out = "out/branch", progress = false})',
                        "b:run_to(0.004)", "b:close()",
                        'sim2 = beltsim.resume("out/scenario/ck/t.ckpt", {rewind = true, progress = false})',
                        "sim2:run_to(0.008)", "sim2:close()"])
        err = r.stderr.decode()
        self.assertEqual(r.returncode, 0, r.stdout.decode() + err)
        session_dir = os.path.join(self.tmp, "out", "scenario")
        with open(os.path.join(session_dir, "session.lua")) as f:
            text = f.read()
        replay_line = text.splitlines()[1]
        self.assertTrue(replay_line.startswith("-- Replay with: beltsim run "), text)
        self.assertIn("--out out/scenario/replay", replay_line)

        def files():  # every file of the session's folder but the replays' (replay/, replay2/): bytes and mtime
            got = {}
            for root, dirs, names in os.walk(session_dir):
                dirs[:] = [d for d in dirs if not (root == session_dir and d.startswith("replay"))]
                for n in names:
                    p = os.path.join(root, n)
                    with open(p, "rb") as f:
                        got[os.path.relpath(p, session_dir)] = (f.read(), os.stat(p).st_mtime_ns)
            return got
        before = files()
        self.assertIn(os.path.join("ck", "t.ckpt"), before)
        with open(os.path.join(self.tmp, "out", "branch", "timeseries.csv"), "rb") as f:
            branch = f.read()
        argv = shlex.split(replay_line[len("-- Replay with: "):])
        r = subprocess.run([BELTSIM] + argv[1:], cwd=self.tmp, env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        out = (r.stdout + r.stderr).decode()
        self.assertEqual(r.returncode, 0, out + "\nsession.lua:\n" + text)
        self.assertEqual(files(), before, "the replay changed the session's folder: " + out)
        with open(os.path.join(session_dir, "timeseries.csv"), "rb") as f:
            series = f.read()
        with open(os.path.join(session_dir, "replay", "timeseries.csv"), "rb") as f:
            self.assertEqual(f.read(), series, "the replay's timeseries.csv differs; " + out)
        self.assertIn(b"\n0.008,", series)
        with open(os.path.join(self.tmp, "out", "branch", "timeseries.csv"), "rb") as f:
            self.assertEqual(f.read(), branch, "the replay changed the session's branch: " + out)
        with open(os.path.join(session_dir, "replay", "branch", "timeseries.csv"), "rb") as f:
            self.assertEqual(f.read(), branch, "the replay's branch differs from the session's: " + out)
        self.assertIn("the session's branch into out/branch goes into out/scenario/replay/branch, in the replay's own "
                      "folder, instead", out)
        self.assertIn("out/scenario/replay/ck/t.ckpt (this replay's copy of the session's out/scenario/ck/t.ckpt) "
                      "resumed at t = 0.003 s; its outputs go on in out/scenario/replay", out)
        self.assertIn('\nbeltsim.replay_of("out/scenario")\n', text)

        # a replay whose own copy is missing (the session.lua without its sim:save) is refused,
        # naming it, and never falls back to the session's checkpoint
        with open(os.path.join(session_dir, "nosave.lua"), "w") as f:
            f.write(text.replace('sim:save("ck/t.ckpt")\n', ""))
        before = files()
        r = subprocess.run([BELTSIM, "run", "out/scenario/nosave.lua", "--out", "out/scenario/replay2"], cwd=self.tmp,
                           env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        err = r.stderr.decode()
        self.assertEqual(r.returncode, 1, err)
        self.assertIn("beltsim.resume: out/scenario/ck/t.ckpt lies in out/scenario, the folder of the session this "
                      "script replays, and continues its outputs; a replay resumes its own copy instead, "
                      "out/scenario/replay2/ck/t.ckpt, and that is not there", err)
        self.assertEqual(files(), before, "the refused replay changed the session's folder: " + err)

        # a replay into the session's own folder is refused before it runs anything
        r = subprocess.run([BELTSIM, "run", "out/scenario/session.lua", "--out", "out/scenario"], cwd=self.tmp,
                           env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        err = r.stderr.decode()
        self.assertEqual(r.returncode, 1, err)
        self.assertIn("beltsim.replay_of: this replay's outputs would go into out/scenario, the folder of the "
                      "session it replays", err)
        self.assertEqual(files(), before, "the refused replay changed the session's folder: " + err)

    # 10b
    def test_a_second_session_keeps_the_first_ones_record(self):
        # two consoles in one output folder (a checkpoint resumed where it was saved): each
        # session's commands in a file of its own, the first's left as it was
        paths = []
        for command in ["sim:advance(0.001)", "print(6*7)"]:
            r = self.piped([command])
            err = r.stderr.decode()
            self.assertEqual(r.returncode, 0, err)
            m = re.search(r"the session's commands are in (\S+)", err)
            self.assertTrue(m, "where the session's commands went is not said: " + err)
            paths.append(os.path.join(self.tmp, m.group(1)))
        self.assertTrue(paths[0].endswith(os.sep + "session.lua"), paths)
        self.assertEqual(paths[1], paths[0][:-len("session.lua")] + "session_2.lua")
        with open(paths[0]) as f:
            self.assertIn("\nsim:advance(0.001)\n", f.read())
        with open(paths[1]) as f:
            self.assertIn("\nprint(6*7)\n", f.read())

    # 10a
    def test_session_replays_expressions_statements_and_chunks(self):
        # bare expressions (printed at the prompt), a chunk that returns, locals, a multi-line
        # chunk and a trailing comment: session.lua is valid Lua and its replay does what the
        # prompt did: what the prompt printed is printed as the prompt showed it (a user's `r`, a
        # table, was recorded as print(r), which printed "table: 0x55d0..."), but the values of a
        # call (the last command's), which the replay makes but does not print
        commands = ["6*7", "sim.t", "return 6*7", "local z = 3", "print(z)",
                    "for i = 1, 2 do", "  print('loop', i)", "end",
                    "function f()", "  return 5", "end", "f() + 1 -- a comment", "sim:advance(0.001)",
                    "local w = 4 return w", 'r = sim:pulley("driven")', "r", "r.omega, sim.t",
                    'sim:pulley("driven")']
        r = self.piped(commands, args=[os.path.join(self.tmp, "out_console")])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        m = re.search(r"the session's commands are in (\S+)", err)
        self.assertTrue(m, "where session.lua went is not said: " + err)
        session = os.path.join(self.tmp, m.group(1))
        with open(session) as f:
            text = f.read()
        # what was typed, then what prints it as the prompt did
        self.assertIn("\n-- > r\nbeltsim.print(r)\n", text)
        self.assertNotIn("\nprint(r)", text)
        for call in ["print(z)", "sim:advance(0.001)", 'sim:pulley("driven")']:  # as typed
            self.assertIn("\n%s\n" % call, text)
        # the scenario's run writes beside it, outside session.lua's folder: --trusted
        r = subprocess.run([BELTSIM, "run", "--trusted", session], cwd=self.tmp, env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        replay = r.stdout.decode()
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        # 6*7, sim.t (0 before the advance), 6*7, z (local to its own command, as at the prompt),
        # the loop, f() + 1, then (the run's result, printed at the prompt only) w, r's table, its
        # speed and t; the last command's table at the prompt only
        self.assertEqual(out.split("\n")[:7], ["42", "0", "42", "nil", "loop\t1", "loop\t2", "6"], out)
        run = out.index("{\n  interrupted")
        pulley = out.index("}\n", run) + 2
        self.assertEqual(replay, out[:run] + out[pulley:out.rindex("{\n  angle")], "session.lua:\n" + text)
        self.assertIn("\n  omega = ", replay)

    # 10b
    def test_session_quotes_set_values(self):
        # a --set value with spaces, a quote, a dollar sign and a newline: session.lua's replay
        # line stays one comment line and gives the shell the same value back (run through bash)
        value = "two words, it's $HOME\nand a second line"
        r = self.piped(["print('<' .. beltsim.args.label .. '>')"], flags=["--set", "label=" + value])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertIn("<" + value + ">", out)
        m = re.search(r"the session's commands are in (\S+)", err)
        self.assertTrue(m, "where session.lua went is not said: " + err)
        with open(os.path.join(self.tmp, m.group(1))) as f:
            text = f.read()
        replay = [l for l in text.splitlines() if l.startswith("-- Replay with: beltsim run ")]
        self.assertEqual(len(replay), 1, text)
        cmd = replay[0][len("-- Replay with: beltsim run "):]
        # the scenario's own run writes beside it, outside session.lua's folder: --trusted
        r = subprocess.run(["bash", "-c", "%s run --trusted %s" % (shlex.quote(BELTSIM), cmd)], cwd=self.tmp,
                           env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        self.assertIn("<" + value + ">", r.stdout.decode(), text)

    # 10d
    def test_session_with_files_in_subfolders_replays_beside_it(self):
        # a trial's session (--out out/mycon) saved sim:save("ck/t033.ckpt"): it went to ./ck/ (a path
        # with a folder was taken from the working folder), and its replay, sandboxed in session.lua's
        # folder, was refused. Now the relative paths lie in the output folder, the replay line gives
        # --out out/mycon/replay, and the replay writes the same files there, without --trusted
        with open(os.path.join(self.tmp, "mydrive.lua"), "w") as f:
            f.write(two_pulley(40) + "sim = drive:start{}\n")
        commands = ["sim:advance(0.003)", "print(sim:save('ck/t.ckpt'))", "sim:advance(0.002)",
                    "print(sim:plot{ file = 'pics/p.png' })"]
        r = subprocess.run([BELTSIM, "console", "mydrive.lua", "--out", "out/mycon"], cwd=self.tmp,
                           input="".join(c + "\n" for c in commands).encode(), env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertIn("out/mycon/ck/t.ckpt\n", out, err)
        self.assertTrue(os.path.isfile(os.path.join(self.tmp, "out", "mycon", "ck", "t.ckpt")), out + err)
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "ck")), out + err)
        with open(os.path.join(self.tmp, "out", "mycon", "session.lua")) as f:
            text = f.read()
        replay = [ln for ln in text.splitlines() if ln.startswith("-- Replay with: beltsim run ")]
        self.assertEqual(replay, ["-- Replay with: beltsim run out/mycon/session.lua --out out/mycon/replay"], text)
        cmd = "%s run %s" % (shlex.quote(BELTSIM), replay[0][len("-- Replay with: beltsim run "):])
        r = subprocess.run(["bash", "-c", cmd], cwd=self.tmp, env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           timeout=60)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        self.assertIn("out/mycon/replay/ck/t.ckpt\n", r.stdout.decode())
        for f in ["ck/t.ckpt", "pics/p.png"]:
            self.assertTrue(os.path.isfile(os.path.join(self.tmp, "out", "mycon", "replay", f)), f)
        for f in ["timeseries.csv", "events.csv"]:
            with open(os.path.join(self.tmp, "out", "mycon", f), "rb") as a, \
                    open(os.path.join(self.tmp, "out", "mycon", "replay", f), "rb") as b:
                self.assertEqual(a.read(), b.read(), f)
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "out", "session")))

    def test_resume_of_sim_saves_path_names_the_file_it_wrote(self):
        # trial 22: sim:save("ck/t03.ckpt") wrote out/live_dry/ck/t03.ckpt, and beltsim.resume("ck/t03.ckpt")
        # said only "No such file or directory" (it reads from the working folder). It names the file
        with open(os.path.join(self.tmp, "mydrive.lua"), "w") as f:
            f.write(two_pulley(40) + "sim = drive:start{}\n")
        commands = ["sim:advance(0.003)", "sim:save('ck/t.ckpt')", "sim:close()", "sim2 = beltsim.resume('ck/t.ckpt')"]
        r = subprocess.run([BELTSIM, "console", "mydrive.lua", "--out", "out/mycon"], cwd=self.tmp,
                           input="".join(c + "\n" for c in commands).encode(), env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 1, out + err)
        self.assertIn("stdin:1: beltsim.resume: ck/t.ckpt: no such file in the folder beltsim runs in, where "
                      "beltsim.resume reads; sim:save(\"ck/t.ckpt\") wrote out/mycon/ck/t.ckpt (sim:save takes a "
                      "relative path inside the simulation's output folder): resume \"out/mycon/ck/t.ckpt\", the "
                      "path sim:save returned\n", out + err)

    # the replay line of session.lua (its second line) run through bash, in the test's folder
    def replay_line(self, text, timeout=60, trusted=False):
        replay = [ln for ln in text.splitlines() if ln.startswith("-- Replay with: beltsim run ")]
        self.assertEqual(len(replay), 1, text)
        cmd = "%s run %s%s" % (shlex.quote(BELTSIM), "--trusted " if trusted else "",
                               replay[0][len("-- Replay with: beltsim run "):])
        return subprocess.run(["bash", "-c", cmd], cwd=self.tmp, env=child_env(self.tmp), stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, timeout=timeout)

    def same_outputs(self, a, b, text):
        for f in ["timeseries.csv", "events.csv"]:
            with open(os.path.join(self.tmp, a, f), "rb") as x, open(os.path.join(self.tmp, b, f), "rb") as y:
                self.assertEqual(x.read(), y.read(), "%s differs; session.lua:\n%s" % (f, text))

    # 10e
    def test_session_replays_with_the_consoles_options(self):
        # a trial's session ran with --rtol 1e-3 --integrator esdirk32: its replay line left them
        # out, and the replay ran at the defaults (38 of 42 columns differed). The replay line
        # repeats the options that change a run, and the replay gives the same outputs
        with open(os.path.join(self.tmp, "mydrive.lua"), "w") as f:
            f.write(two_pulley(40) + "sim = drive:start{}\n")
        r = subprocess.run([BELTSIM, "console", "mydrive.lua", "--out", "out/opt", "--rtol", "1e-3", "--integrator",
                            "esdirk32", "--no-frames"], cwd=self.tmp, input=b"sim:advance(0.01)\n",
                           env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode())
        with open(os.path.join(self.tmp, "out", "opt", "session.lua")) as f:
            text = f.read()
        self.assertIn("\n-- Replay with: beltsim run out/opt/session.lua --out out/opt/replay --integrator esdirk32 "
                      "--rtol 1e-3 --no-frames\n", text)
        r = self.replay_line(text)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        with open(os.path.join(self.tmp, "out", "opt", "replay", "parameters.csv")) as f:
            params = f.read()
        self.assertIn("\nrun.integrator,esdirk32,", params)
        self.assertIn("\nrun.rtol,0.001,", params)
        self.same_outputs("out/opt", "out/opt/replay", text)

    # 10f
    def test_session_lua_is_written_as_the_session_goes(self):
        # session.lua was written only at the console's end: a kill -9 lost the whole record. It
        # is written after each command, and a SIGKILL keeps the commands so far
        p = subprocess.Popen([BELTSIM, "console", "scenario.lua"], cwd=self.tmp, env=child_env(self.tmp),
                             stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.addCleanup(p.kill)
        p.stdin.write(b"y = 2\nsim:advance(0.002)\n")
        p.stdin.flush()
        session = os.path.join(self.tmp, "out", "scenario", "session.lua")
        deadline = time.monotonic() + STARTUP_TIMEOUT + TIMEOUT
        text = ""
        while "\nsim:advance(0.002)\n" not in text:
            self.assertLess(time.monotonic(), deadline, "session.lua does not hold the commands run:\n" + text)
            time.sleep(0.05)
            try:
                with open(session) as f:
                    text = f.read()
            except FileNotFoundError:
                pass
        p.kill()
        p.wait(timeout=TIMEOUT)
        p.stdin.close()
        with open(session) as f:
            lines = f.read().splitlines()
        self.assertIn("y = 2", lines)
        self.assertLess(lines.index("y = 2"), lines.index("sim:advance(0.002)"))

    # 10g
    def test_a_run_stopped_by_sigterm_is_recorded_so(self):
        # it was recorded as "stopped by Ctrl-C"
        p = subprocess.Popen([BELTSIM, "console", "scenario.lua"], cwd=self.tmp, env=child_env(self.tmp),
                             stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        self.addCleanup(p.kill)
        p.stdin.write(b"r = sim:advance(100)\n")
        p.stdin.flush()
        self.wait_rows(os.path.join(self.tmp, "out", "timeseries.csv"), 100)
        p.send_signal(signal.SIGTERM)
        _, err = p.communicate(timeout=TIMEOUT)
        self.assertEqual(p.returncode, 143, err.decode())
        with open(os.path.join(self.tmp, "out", "scenario", "session.lua")) as f:
            lines = f.read().splitlines()
        self.assertIn("-- r = sim:advance(100)  -- stopped by SIGTERM", lines)

    # until the CSV has more than n rows (the run under way)
    def wait_rows(self, csv, n):
        deadline = time.monotonic() + STARTUP_TIMEOUT + TIMEOUT
        while True:
            try:
                with open(csv) as f:
                    if f.read().count("\n") > n:
                        return
            except FileNotFoundError:
                pass
            self.assertLess(time.monotonic(), deadline, "no %d rows in %s" % (n, csv))
            time.sleep(0.02)

    # 10h
    def test_a_scenario_run_stopped_at_the_start_replays_to_there(self):
        # Ctrl-C stopped the scenario's scene:run as the console started: session.lua copied the
        # scenario as it is, and the replay ran it to its end. It is replayed to where it stopped
        # (beltsim.stop_at), the scenario going on after it as it did
        with open(os.path.join(self.tmp, "batch.lua"), "w") as f:
            f.write(two_pulley(40) + "r = drive:run{ t_end = 100 }\nprint('after', r.t, r.interrupted)\n")
        p = subprocess.Popen([BELTSIM, "console", "batch.lua", "--no-frames"], cwd=self.tmp, env=child_env(self.tmp),
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.addCleanup(p.kill)
        self.wait_rows(os.path.join(self.tmp, "out", "batch", "timeseries.csv"), 100)
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(b"print('t', r.t)\n", timeout=STARTUP_TIMEOUT + TIMEOUT)
        out, err = out.decode(), err.decode()
        self.assertEqual(p.returncode, 0, out + err)
        m = re.search(r"after\t([0-9.e+-]+)\ttrue\n", out)
        self.assertTrue(m, out + err)
        self.assertLess(float(m.group(1)), 100)
        with open(os.path.join(self.tmp, "out", "batch", "session.lua")) as f:
            text = f.read()
        r = self.replay_line(text)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        self.assertEqual(r.stdout.decode(), out, text)
        self.same_outputs("out/batch", "out/batch/replay", text)

    # 11
    def test_ctrl_c_stops_lua_code(self):
        c = self.console()
        # each loop prints a line as it starts (the echo of the command does not hold that line),
        # so the Ctrl-C comes while Lua code runs
        for loop in ["while true do end", "coroutine.wrap(function() while true do end end)()",
                     "while true do pcall(function() while true do end end) end"]:
            mark = len(c.screen)
            c.send("print('loop' .. 'ing') " + loop + "\r")
            c.wait_for(re.compile(r"\nlooping\r?\n"), start=mark, what="the loop's first line")
            c.send("\x03")
            c.wait_prompt(mark, timeout=5)
            self.assertIn("interrupted!", c.screen[mark:], c.transcript())
            out = c.command("1+1")
            self.assertRegex(out, r"\n2\n", c.transcript())

    # 11b
    def test_lua_code_that_ctrl_c_interrupted_is_not_replayed(self):
        # `while true do end` interrupted by Ctrl-C was replayed under pcall: the replay looped to the
        # instruction limit (25 s) and ended there, the commands after it not run. It is kept as a
        # comment, and the replay runs the rest
        c = self.console()
        c.command("x = 1")
        mark = len(c.screen)
        c.send("print('loop' .. 'ing') while true do end\r")
        c.wait_for(re.compile(r"\nlooping\r?\n"), start=mark, what="the loop's first line")
        c.send("\x03")
        c.wait_prompt(mark, timeout=5)
        c.command("print('x is', x)")
        self.assertEqual(c.eof(), 0, c.transcript())
        with open(os.path.join(self.tmp, "out", "scenario", "session.lua")) as f:
            text = f.read()
        self.assertIn("\n-- (Ctrl-C interrupted it at the prompt: not replayed, as it may not end)\n"
                      "-- print('loop' .. 'ing') while true do end\nprint('x is', x)\n", text)
        # (the scenario's run writes beside it, outside session.lua's folder: --trusted)
        r = self.replay_line(text, trusted=True)
        self.assertEqual(r.returncode, 0, (r.stdout + r.stderr).decode() + "\nsession.lua:\n" + text)
        self.assertEqual(r.stdout.decode(), "x is\t1\n", text)

    # 12
    def test_completion_runs_no_lua_code(self):
        c = self.console()
        c.command("t = setmetatable({}, { __index = function() error('no') end })")
        # no key to complete: readline rings the bell once the completion has ended
        mark = c.complete_nothing("t.a.b")
        c.send("\x03")  # clears the line
        c.wait_prompt(mark)
        out = c.command("1+1")
        self.assertRegex(out, r"\n2\n", c.transcript())

    # 13
    def test_sandbox_and_trusted(self):
        r = self.piped(['os.execute("true")', 'print("after")'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertIn("stdin:1: os.execute is not allowed in a scenario script", err)
        self.assertIn("--trusted", err)
        self.assertIn("after\n", out, err)
        self.assertEqual(r.returncode, 1, out + err)
        r = self.piped(['print(os.execute("true"))'], flags=["--trusted"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 0, out + err)
        self.assertIn("true\texit\t0\n", out, err)

    # 14
    def test_instruction_limit_per_command(self):
        six_million = "local x = 0 for i = 1, 3e6 do x = x + i end"
        r = self.piped([six_million, six_million, "while true do end", 'print("after")'],
                       flags=["--max-instructions", "1e7"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(err.count("instruction limit"), 1, err)
        self.assertIn("stdin:1: the instruction limit was reached: more than 10000000", err)
        self.assertIn("--max-instructions", err)
        self.assertIn("after\n", out, err)
        # the time limit too: the command stops, the console goes on
        r = self.piped(["while true do end", 'print("after")'], flags=["--max-lua-wall", "0.3"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertIn("stdin:1: the wall-time limit of a Lua call was reached: more than 0.3 s", err)
        self.assertIn("after\n", out, err)
        r = subprocess.run([BELTSIM, "run", "scenario.lua", "--max-instructions", "-1"], cwd=self.tmp,
                           env=child_env(self.tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        self.assertEqual(r.returncode, 2, r.stderr.decode())
        self.assertIn("--max-instructions", r.stderr.decode())

    # 15
    def test_a_failing_tostring_is_an_error(self):
        # a table key is printed through its __tostring (Lua code, which may fail)
        r = self.piped(['{ [setmetatable({}, { __tostring = function() error("boom") end })] = 1 }',
                        'print("after")'])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertIn("boom", err)
        self.assertIn("after\n", out, err)

    # 16
    def test_max_wall(self):
        # --max-wall S limits each integration call of the console: the call stops at the last
        # finished step with an error naming the limit and the time reached; the session goes on
        r = self.piped(["sim:advance(10)", 'print("after", sim.t)'], flags=["--max-wall", "0.2"])
        out, err = r.stdout.decode(), r.stderr.decode()
        self.assertEqual(r.returncode, 1, out + err)  # a command failed
        m = re.search(r"stopped at its wall-time limit \(--max-wall 0\.2 s\) at t = ([0-9.e+-]+) s of 10 s", err)
        self.assertTrue(m, err)
        t = float(m.group(1))
        self.assertGreater(t, 0.0, err)
        self.assertLess(t, 10.0, err)
        after = re.search(r"after\t([0-9.e+-]+)\n", out)
        self.assertTrue(after, out + err)
        self.assertAlmostEqual(float(after.group(1)), t, delta=1e-8 * t)  # the message has 10 digits
        # the CSV's rows are whole and reach no further than the time reached
        with open(os.path.join(self.tmp, "out", "timeseries.csv")) as f:
            rows = f.read().splitlines()[1:]
        self.assertTrue(rows, "no samples")
        width = len(rows[0].split(","))
        self.assertTrue(all(len(r.split(",")) == width for r in rows))
        self.assertLessEqual(float(rows[-1].split(",")[0]), t)

    # 17
    def test_wp_with_no_integrators_is_a_usage_error(self):
        # an empty list used to mean "all of them"
        r = subprocess.run([BELTSIM, "wp", "scenario.lua", "--integrators", ""], cwd=self.tmp, env=child_env(self.tmp),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        self.assertEqual(r.returncode, 2, r.stderr.decode())
        self.assertIn("--integrators needs names separated by commas", r.stderr.decode())

    # 18
    def test_completion_inside_strings(self):
        c = self.console()
        # a pulley name; one match closes the string
        mark = c.complete('sim:pulley("dr', 'sim:pulley("drive', "the common part of driver and driven")
        c.send("r\t")  # now one match: the quote is closed
        c.wait_for('sim:pulley("driver"', what='the completion to "driver"', start=mark)
        c.send(").omega\r")
        c.wait_prompt(mark)
        self.assertRegex(c.screen[mark:], r"\n-?[0-9.e+-]+\n> ", c.transcript())  # a number, no error
        # a column in sim:plot's list, in single quotes
        mark = c.complete("sim:plot{ 'driven.slip_sp", "sim:plot{ 'driven.slip_speed'", "the completion of a column")
        c.send("\x03")
        c.wait_prompt(mark)
        # a field of a table argument, both matches listed on a second Tab
        mark = c.complete('sim:elements{ pulley = "drive', re.compile(r"driven\s+driver"),
                          "the list of the two pulleys", tabs="\t\t")
        c.send("\x03")
        c.wait_prompt(mark)
        # help's entries
        mark = c.complete('help("set_to', 'help("set_torque"', "the completion of a help entry")
        c.send(")\r")
        c.wait_prompt(mark)
        self.assertIn("sim:set_torque(name, law", c.screen[mark:], c.transcript())
        # a string that is no call's argument completes nothing
        mark = c.complete_nothing('x = "dr')
        c.send("\x03")
        c.wait_prompt(mark)

    # 19
    # Python's bare words: help lists the API, exit leaves as Ctrl-D does (session written, status 0);
    # a script that keeps no globals is told how to keep one
    def test_bare_help_and_exit_and_a_script_without_globals(self):
        c = self.console()
        out = c.command("help")
        self.assertIn("sim:advance(dt [s])", out, c.transcript())
        self.assertNotIn("function: 0x", out, c.transcript())
        # padded by characters: the N·m entry lines up with the others
        lines = [ln for ln in out.splitlines() if ln.startswith("  sim:set_torque(") or ln.startswith("  sim:set_speed(")]
        self.assertEqual(len(lines), 2, c.transcript())
        self.assertEqual(lines[0].index(" a new torque"), lines[1].index(" a prescribed"), c.transcript())
        c.send("exit\r")
        deadline = time.monotonic() + TIMEOUT
        while c.pump(deadline - time.monotonic()):
            if time.monotonic() > deadline:
                self.fail("the console did not end after exit" + c.transcript())
        self.assertEqual(c._reap(deadline), 0, c.transcript())
        self.assertTrue(os.path.exists(os.path.join(self.tmp, "out", "scenario", "session.lua")), c.transcript())
        with open(os.path.join(self.tmp, "local.lua"), "w") as f:
            f.write("local x = 1\n")
        c = Console(BELTSIM, self, self.tmp, script="local.lua")
        self.consoles.append(c)
        self.assertIn("local.lua left no globals", c.screen, c.transcript())


def main():
    global BELTSIM
    if len(sys.argv) < 2:
        sys.exit("usage: console_test.py PATH/TO/beltsim [unittest options]")
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)


if __name__ == "__main__":
    main()
