#!/usr/bin/env python3
"""The progress line and the line a run ends with (src/script/progress.cpp): `beltsim run` on a
pseudo-terminal, where the progress line is redrawn in place, and through a pipe, where it is not.

Usage: progress_test.py PATH/TO/beltsim [unittest options]

A user met a warning printed onto the progress line ("... 10239 steps   beltsim: warning: ..."), a
progress line left at "(94 %)" above a run that had ended, and a batch run that ended in silence.
The runs here are slowed by Lua code that waits on the CPU clock (in a callback, in a law), so that
they take seconds, and their progress shows, on a machine of any speed.
"""

import os
import pty
import re
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import termios
import time
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "console"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from pty_console import child_env  # noqa: E402  (tests/console/pty_console.py)
from scenes import two_pulley  # noqa: E402

BELTSIM = None  # set from argv in main

# each ms of simulated time takes 20 ms of the CPU: 0.15 s simulated take 3 s at least
WAIT = "local function wait(s) local c = os.clock() while os.clock() - c < s do end end\n"

# a live simulation whose callback prints (stdout) 1.5 s into the run and makes a scene (its notes
# on stderr) 1 s later, while the progress line is showing; the run goes on for 1.5 s more
LIVE = (two_pulley(40) + WAIT +
        'local sim = drive:start { out = "live" }\n'
        "local c0, printed, made = os.clock(), false, false\n"
        "sim:every(0.001, function()\n"
        "  wait(0.02)\n"
        "  if not printed and os.clock() - c0 > 1.5 then\n"
        "    printed = true\n"
        "    print('printed by the callback')\n"
        "  end\n"
        "  if not made and os.clock() - c0 > 2.5 then\n"
        "    made = true\n"
        "    beltsim.scene { pulleys = { { name = 'a', centre = {0, 0}, radius = 0.1, speed = -10 },\n"
        "                                { name = 'b', centre = {0.29, 0}, radius = 0.1 } },\n"
        "                    belt = { elements = 20, pretension = 500, direction = 'cw' } }\n"
        "  end\n"
        "end)\n"
        "sim:run_to(0.2)\n"
        "sim:close()\n")

# a live simulation whose callback writes with io.write 1.5 s into the run, with io.stdout:write 1 s
# later and with io.stderr:write 1 s after that, while the progress line is showing
WRITES = (two_pulley(40) + WAIT +
          'local sim = drive:start { out = "writes" }\n'
          "local c0, written = os.clock(), 0\n"
          "sim:every(0.001, function()\n"
          "  wait(0.02)\n"
          "  if written == 0 and os.clock() - c0 > 1.5 then written = 1; io.write('written by io.write', '\\n') end\n"
          "  if written == 1 and os.clock() - c0 > 2.5 then written = 2; io.stdout:write('written to io.stdout\\n') end\n"
          "  if written == 2 and os.clock() - c0 > 3.5 then written = 3; io.stderr:write('written to io.stderr\\n') end\n"
          "end)\n"
          "sim:run_to(0.25)\n"
          "sim:close()\n")

# a batch run whose driver's torque law waits 20 ms once per ms of simulated time: 0.15 s simulated
# take 3 s at least
BATCH = ("local next_t = 0\n" + WAIT +
         two_pulley(40).replace("torque = beltsim.ramp(0.3, -70)",
                                "torque = function(t) if t >= next_t then next_t = next_t + 0.001; wait(0.02) end "
                                "return -70 * math.min(t / 0.3, 1) end") +
         'drive:run { t_end = 0.15, out = "batch" }\n')

# a live run of 3 s at least (a callback waits 20 ms per ms of simulated time) whose callback does
# THEN once, 2.5 s of the CPU into the run (wall time at least as long: the progress line shows),
# after printing "then now"
SLOW = (two_pulley(40) + WAIT +
        'local sim = drive:start { out = "slow" }\n'
        "local c0, done = os.clock(), false\n"
        "sim:every(0.001, function()\n"
        "  wait(0.02)\n"
        "  if not done and os.clock() - c0 > 2.5 then done = true; print('then now'); THEN end\n"
        "end)\n"
        "sim:run_to(0.2)\n"
        "sim:close()\n")
# a C call that Lua cannot stop (a string pattern that backtracks for minutes)
STUCK = 'local x = ("a"):rep(3000):find("(.-)(.-)(.-)(.-)b")'

# a scene whose build takes seconds on any machine: its driver's torque law, which the static
# solve evaluates with every residual (428 times for this belt), waits 8 ms of the CPU
SLOW_BUILD = (WAIT + two_pulley(40).replace("torque = beltsim.ramp(0.3, -70)",
                                            "torque = function(t) wait(0.008) return -70 * math.min(t / 0.3, 1) end") +
              'print("built")\n')

# the README's minimal scenario (a run of a fraction of a second: no progress line)
MINIMAL = two_pulley(60) + "drive:run { t_end = 0.1 }\n"


def spawn_on_terminal(argv, cwd):
    """Starts argv with a pseudo-terminal as its stdin, stdout and stderr; returns (pid, the
    terminal's descriptor)."""
    pid, fd = pty.fork()
    if pid == 0:
        try:
            os.chdir(cwd)
            os.execve(argv[0], argv, child_env(cwd))
        except BaseException as e:  # noqa: BLE001 (the child must never return into unittest)
            os.write(2, ("cannot start %s: %s\n" % (argv[0], e)).encode())
        finally:
            os._exit(127)
    return pid, fd


def read_to_end(pid, fd, raw=b"", timeout=120):
    """Reads the terminal until the child closes it (or timeout), then reaps the child; returns
    (exit status, raw and what followed it, as text)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            data = os.read(fd, 65536)
        except OSError:  # EIO: the child has closed the terminal
            break
        if not data:
            break
        raw += data
    _, status = os.waitpid(pid, 0)
    os.close(fd)
    return os.waitstatus_to_exitcode(status), raw.decode("utf-8", "replace")


def echoes(fd):
    """Whether the terminal (the pseudo-terminal whose master is fd) echoes what is typed."""
    return bool(termios.tcgetattr(fd)[3] & termios.ECHO)


def read_until(fd, raw, text, timeout=60):
    """Reads the terminal until text (bytes) has come after raw's end; returns what was read, raw included."""
    start, deadline = len(raw), time.monotonic() + timeout
    while text not in raw[start:]:
        if time.monotonic() > deadline:
            raise AssertionError("no %r within %g s: %r" % (text, timeout, raw))
        r, _, _ = select.select([fd], [], [], max(0.0, deadline - time.monotonic()))
        if r:
            try:
                data = os.read(fd, 65536)
            except OSError:
                data = b""
            if not data:
                raise AssertionError("the terminal closed before %r: %r" % (text, raw))
            raw += data
    return raw


def to_end_echo(pid, fd, raw=b"", timeout=120):
    """read_to_end, and whether the terminal echoes once the child has gone: (exit status, text, echoes)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            data = os.read(fd, 65536)
        except OSError:
            break
        if not data:
            break
        raw += data
    _, status = os.waitpid(pid, 0)
    echo = echoes(fd)  # the terminal as the child left it (the master keeps it)
    os.close(fd)
    return os.waitstatus_to_exitcode(status), raw.decode("utf-8", "replace"), echo


def on_terminal(argv, cwd, timeout=120):
    """Runs argv on a pseudo-terminal (spawn_on_terminal); returns (exit status, the bytes written,
    as text)."""
    pid, fd = spawn_on_terminal(argv, cwd)
    return read_to_end(pid, fd, timeout=timeout)


def progress_texts(raw):
    """Each drawing of the progress line, in order."""
    return re.findall(r"beltsim: t = [0-9.]+ s of [^\r\n]*?steps", raw)


class ProgressTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_progress_")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def script(self, name, text):
        with open(os.path.join(self.dir, name), "w") as f:
            f.write(text)
        return name

    def test_a_message_during_a_run_starts_its_own_line(self):
        code, raw = on_terminal([BELTSIM, "run", self.script("live.lua", LIVE)], self.dir)
        self.assertEqual(code, 0, raw)
        drawn = progress_texts(raw)
        self.assertTrue(drawn, "no progress line: %r" % raw)
        # every line starts at the start of a line, the run's messages and the script's print too:
        # none follows the progress line's text on its terminal line
        printed, noted = raw.find("printed by the callback"), raw.rfind("beltsim: scene defaults")
        for said, at in [("the print", printed), ("the scene's note", noted)]:
            self.assertGreater(at, raw.find(drawn[0]), "%s before any progress line: %r" % (said, raw))
            self.assertEqual(raw[at - 1], "\n", "%s follows %r" % (said, raw[max(0, at - 120):at + 40]))
        self.assertTrue(re.search(r"beltsim: t = [^\n]*\n[^\n]*printed by the callback", raw), raw)
        self.assertTrue(re.search(r"beltsim: t = [^\n]*\n[^\n]*scene defaults", raw[printed:]), raw)
        # and the progress line goes on below them
        self.assertGreater(raw.rfind("beltsim: t = "), noted, raw)

    def test_a_scripts_writes_start_their_own_line(self):
        # io.write and a file's write to stdout or stderr, as print: each after a progress line
        # drawn, at the start of a line of its own, and the progress goes on below them
        code, raw = on_terminal([BELTSIM, "run", self.script("writes.lua", WRITES)], self.dir)
        self.assertEqual(code, 0, raw)
        last = 0
        for text in ["written by io.write", "written to io.stdout", "written to io.stderr"]:
            at = raw.find(text)
            self.assertGreater(at, last, "%s missing or out of order: %r" % (text, raw))
            self.assertRegex(raw[last:at + len(text)], r"beltsim: t = [^\r\n]*steps( \(lately [^)]*\))? *\r?\n" + re.escape(text) + "$",
                             "%s does not follow a progress line, on a line of its own: %r" % (text, raw))
            last = at
        self.assertGreater(raw.rfind("beltsim: t = "), last, raw)

    def test_the_progress_line_shows_the_end(self):
        for name, text in [("live.lua", LIVE.replace("sim:run_to(0.2)", "sim:run_to(0.15)")), ("batch.lua", BATCH)]:
            code, raw = on_terminal([BELTSIM, "run", self.script(name, text)], self.dir)
            self.assertEqual(code, 0, raw)
            drawn = progress_texts(raw)
            self.assertTrue(drawn, "%s: no progress line: %r" % (name, raw))
            # the last drawing is the end: all of the time, nothing left, then the line is closed
            self.assertRegex(drawn[-1], r"^beltsim: t = 0\.1500 s of 0\.15 s \(100 %\), [0-9]+ s elapsed, [0-9]+ steps$",
                             name)
            self.assertRegex(raw[raw.rfind(drawn[-1]):], r"^[^\r\n]*steps *\r\n", name)

    def test_the_line_says_how_long_the_steps_are_lately(self):
        # each drawing but the last gives the mean step since the one before it: a run held to tiny
        # steps shows why its estimate is hours (a user's trial: rkf45's 7 ns steps went unsaid)
        code, raw = on_terminal([BELTSIM, "run", self.script("batch.lua", BATCH)], self.dir)
        self.assertEqual(code, 0, raw)
        form = r"beltsim: t = ([0-9.]+) s of [^\r\n]*?, ([0-9]+) steps \(lately ([0-9.e+-]+) s each\)"
        drawn = [(float(t), int(n), float(h)) for t, n, h in re.findall(form, raw)]
        self.assertGreaterEqual(len(drawn), 2, raw)
        for (t1, n1, _), (t2, n2, h) in zip(drawn, drawn[1:]):
            # (the times are written to 4 decimals, the step to 2 significant digits)
            self.assertAlmostEqual(h, (t2 - t1) / (n2 - n1), delta=0.05 * h + 1e-4 / (n2 - n1))
        self.assertNotIn("lately", progress_texts(raw)[-1])

    def test_a_run_stopped_shows_where(self):
        # Ctrl-C (SIGINT) once the progress shows (the run's own code, no Lua code that ^C would
        # interrupt): the line shows where it stopped, not what was left; the closing line too, a
        # batch run's as it returns and a live simulation's as sim:close() closes it
        for name, run in [("long.lua", 'drive:run { t_end = 10, out = "long" }\n'),
                          ("long_live.lua", 'local sim = drive:start { out = "long" }\nsim:run_to(10)\nsim:close()\n')]:
            path = os.path.join(self.dir, self.script(name, two_pulley(40) + run))
            pid, fd = spawn_on_terminal([BELTSIM, "run", path], self.dir)
            raw, deadline = b"", time.monotonic() + 60
            while b"beltsim: t = " not in raw and time.monotonic() < deadline:
                raw += os.read(fd, 65536)
            os.write(fd, b"\x03")
            code, text = read_to_end(pid, fd, raw)
            self.assertEqual(code, 130, name + ": " + text)
            drawn = progress_texts(text)
            self.assertRegex(drawn[-1], r"^beltsim: t = [0-9.]+ s of 10 s \(\d+ %\), [0-9]+ s elapsed, [0-9]+ steps$", name)
            self.assertRegex(text, r"\nbeltsim: run stopped at t = [0-9.]+ s of 10 s \([0-9]+ steps, [0-9.]+ s\): "
                             r"long/\r\n", name)

    def test_keys_typed_during_a_run_are_not_echoed_onto_its_line(self):
        # a user typed while a run's progress showed: the terminal echoed the keys onto the line
        # ("... 57997 stepsbcllo there"); the terminal's echo is off while the line shows, on again
        # after the run, and what was typed is left to the shell (not read by beltsim)
        path = self.script("slow.lua", SLOW.replace("THEN", "wait(0.5)"))
        pid, fd = spawn_on_terminal([BELTSIM, "run", path], self.dir)
        self.assertTrue(echoes(fd), "the terminal did not echo to begin with")
        raw = read_until(fd, b"", b"beltsim: t = ")
        self.assertFalse(echoes(fd), "the terminal echoes while the progress line shows: %r" % raw)
        os.write(fd, b"typed ahead")
        code, text, echo = to_end_echo(pid, fd, raw)
        self.assertEqual(code, 0, text)
        self.assertNotIn("typed ahead", text)
        self.assertTrue(echo, "the run left the terminal without echo: %r" % text)

    def test_the_echo_comes_back_however_the_run_ends(self):
        # the progress line showing (the echo off), the run ends by Ctrl-C, by an error in its
        # callback, by a second Ctrl-C in a C call Lua cannot stop (the process quits at once), by
        # SIGTERM there (the watchdog ends it), and by the end of the Lua call's wall-time limit
        # there (_exit): the terminal echoes again each time
        cases = [("ctrl_c", "wait(1)", [], 130), ("error", 'wait(1); error("boom")', [], 1),
                 ("second_ctrl_c", STUCK, [], -signal.SIGINT), ("sigterm", STUCK, [], -signal.SIGTERM),
                 ("time_limit", STUCK, ["--max-lua-wall", "1"], 1)]
        for name, then, flags, status in cases:
            with self.subTest(name):
                path = self.script(name + ".lua", SLOW.replace("THEN", then))
                pid, fd = spawn_on_terminal([BELTSIM, "run"] + flags + [path], self.dir)
                raw = read_until(fd, b"", b"then now")
                self.assertFalse(echoes(fd), "%s: the terminal echoes while the progress line shows: %r" % (name, raw))
                if name in ("ctrl_c", "second_ctrl_c"):
                    os.write(fd, b"\x03")
                if name == "second_ctrl_c":
                    raw = read_until(fd, raw, b"Ctrl-C again ends beltsim")
                    os.write(fd, b"\x03")
                if name == "sigterm":
                    os.kill(pid, signal.SIGTERM)
                code, text, echo = to_end_echo(pid, fd, raw)
                self.assertEqual(code, status, text)
                self.assertTrue(echo, "%s: the run left the terminal without echo: %r" % (name, text))

    def test_a_long_scene_build_shows_its_progress(self):
        # a belt of 19 000 elements took 20 s to build without a word: a build that takes more than
        # a second shows the progress line (its stage, wall time, Newton iterations) and ends it
        # with the scene built, before the scene's own lines
        code, raw = on_terminal([BELTSIM, "run", self.script("slow_build.lua", SLOW_BUILD)], self.dir)
        self.assertEqual(code, 0, raw)
        drawn = re.findall(r"beltsim: (?:building the scene|scene built) [^\r\n]*", raw)
        self.assertTrue(drawn, "no progress line of the build: %r" % raw)
        self.assertRegex(drawn[0], r"^beltsim: building the scene \(40 elements\): static state, [0-9]+ s elapsed, "
                         r"Newton iteration [0-9]+(: [0-9.e+-]+ m/s² from equilibrium)?$")
        self.assertRegex(drawn[-1], r"^beltsim: scene built \(40 elements\), [0-9]+ s elapsed, [0-9]+ Newton iterations *$")
        self.assertLess(raw.index(drawn[-1]), raw.index("beltsim: scene defaults"), raw)
        self.assertRegex(raw[raw.index(drawn[-1]):], r"^[^\r\n]*\r\nbeltsim: scene defaults", raw)
        # a quick build says nothing of it
        code, raw = on_terminal([BELTSIM, "run", self.script("my.lua", MINIMAL)], self.dir)
        self.assertEqual(code, 0, raw)
        self.assertNotIn("building the scene", raw)
        self.assertNotIn("scene built", raw)

    def test_the_percentage_is_of_the_time_the_line_names(self):
        # trial 12: a live simulation's run_to(0.15) then run_to(0.4) read "t = 0.1834 s of 0.4 s (13 %)",
        # the share of the second call (from 0.15 s); the share is of the time from the simulation's start
        segments = (two_pulley(40) + WAIT + 'local sim = drive:start { out = "segments" }\n'
                    "sim:every(0.001, function() wait(0.02) end)\n"
                    "sim:run_to(0.05)\nsim:run_to(0.15)\nsim:close()\n")
        code, raw = on_terminal([BELTSIM, "run", self.script("segments.lua", segments)], self.dir)
        self.assertEqual(code, 0, raw)
        second = [d for d in progress_texts(raw) if " of 0.15 s " in d]
        shares = [(float(m.group(1)), int(m.group(2)))
                  for m in (re.match(r"beltsim: t = ([0-9.]+) s of 0\.15 s \((\d+) %\)", d) for d in second)]
        self.assertTrue([t for t, _ in shares if t < 0.14], "no drawing of the second run_to before its end: %r" % raw)
        for t, share in shares:
            self.assertLessEqual(abs(share - 100 * t / 0.15), 1, raw)

    def test_a_run_says_where_it_ended(self):
        # the README's minimal run: one line on stderr names the end, the steps, the time and the outputs
        name = self.script("my.lua", MINIMAL)
        p = subprocess.run([BELTSIM, "run", name], cwd=self.dir, env=child_env(self.dir), capture_output=True,
                           text=True, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout, "")
        last = p.stderr.splitlines()[-1]
        self.assertRegex(last, r"^beltsim: run ended at t = 0\.1 s \([0-9]+ steps, [0-9.]+ s\): out/my/$", p.stderr)
        # progress = false: neither the progress nor that line
        quiet = self.script("quiet.lua", MINIMAL.replace("t_end = 0.1", "t_end = 0.1, progress = false"))
        p = subprocess.run([BELTSIM, "run", quiet], cwd=self.dir, env=child_env(self.dir), capture_output=True,
                           text=True, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertNotIn("run ended", p.stderr)

    def test_a_live_simulation_says_where_it_ended(self):
        # sim:close() of a simulation that ran says what scene:run{} says, once, with the steps and
        # wall time of its runs (run_to and advance); not for one that did not run, nor with
        # progress = false
        name = self.script("live_end.lua", two_pulley(60) +
                           "local sim = drive:start {}\n"
                           "local a, b = sim:run_to(0.05), sim:advance(0.05)\n"
                           "sim:close()\n"
                           "sim:close()\n"
                           "print(a.steps + b.steps)\n"
                           'drive:start { out = "idle" }:close()\n'
                           'local quiet = drive:start { out = "quiet", progress = false }\n'
                           "quiet:run_to(0.01)\n"
                           "quiet:close()\n")
        p = subprocess.run([BELTSIM, "run", name], cwd=self.dir, env=child_env(self.dir), capture_output=True,
                           text=True, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        ended = [line for line in p.stderr.splitlines() if "run ended" in line]
        self.assertEqual(len(ended), 1, p.stderr)
        self.assertRegex(ended[0], r"^beltsim: run ended at t = 0\.1 s \(%s steps, [0-9.]+ s\): out/live_end/$"
                         % p.stdout.strip(), p.stderr)

    def test_a_batch_run_stopped_by_max_wall_says_where_and_its_warnings(self):
        # a user's trial: a batch run that --max-wall stopped, in a log, said neither where it had
        # stopped nor the fallbacks it had needed, as a stopped live run and Ctrl-C's stop do. The
        # serpentine drive (200 elements) fails a step at 0.017 s, reached well inside its 1 s
        shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "serpentine.lua"),
                    self.dir)
        p = subprocess.run([BELTSIM, "run", "serpentine.lua", "--set", "n=200", "--set", "t_end=3", "--max-wall", "1"],
                           cwd=self.dir, env=child_env(self.dir), capture_output=True, text=True, timeout=120)
        self.assertEqual(p.returncode, 1, p.stderr)
        with open(os.path.join(self.dir, "out", "serpentine", "parameters.csv")) as f:
            self.assertRegex(f.read(), r"\nwarning\.failed_step\.count,[1-9]")
        last = p.stderr.splitlines()[-3:]
        self.assertRegex(last[0], r"^beltsim: warnings: failed_step [0-9]+ times? \(first at t = 0\.01", p.stderr)
        self.assertRegex(last[1], r"^beltsim: run stopped at t = [0-9.]+ s of 3 s \([0-9]+ steps, [0-9.]+ s\): "
                         r"out/serpentine/$", p.stderr)
        # the limit named where it was given: the command line's --max-wall, not the script's run.max_wall
        self.assertRegex(last[2], r"^beltsim: serpentine\.lua:[0-9]+: the run stopped at its wall-time "
                         r"limit \(--max-wall 1 s\)", p.stderr)

    def test_a_log_has_no_redraws(self):
        # stderr a pipe (a CI log): no carriage returns, the progress every 10 s only, the end once,
        # the closing line last
        name = self.script("batch.lua", BATCH)
        p = subprocess.run([BELTSIM, "run", name], cwd=self.dir, env=child_env(self.dir), capture_output=True,
                           text=True, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertNotIn("\r", p.stderr)
        self.assertRegex(p.stderr.splitlines()[-1], r"^beltsim: run ended at t = 0\.15 s \([0-9]+ steps, [0-9.]+ s\): "
                         r"batch/$")


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
