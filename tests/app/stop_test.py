#!/usr/bin/env python3
"""Every call stoppable (src/script/signals.cpp): SIGTERM ends `beltsim run` and the console whatever
Lua is doing, including what the Lua hook cannot reach (an xpcall message handler that loops runs
with hooks off; a backtracking string pattern is one long C call), as does a second Ctrl-C; Lua
code that goes on after a stopped run stops too; SIGHUP is handled as SIGTERM (exit 129, the video
finalised). Each case waits for the event it needs (a line the script prints, a file, a message)
and gives the process 5 s to end after the signal.

usage: stop_test.py BELTSIM
"""
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None
LIMIT = 5.0  # [s] from the signal to the end of the process

# one long C call: string.find backtracks over 3000^4 / 24 positions (hours)
PATTERN = 'print(string.rep("a", 3000):find(".-.-.-.-b"))'
# a message handler that loops: Lua runs it with hooks off
HANDLER = "xpcall(function() error('x') end, function(m) while true do end end)"
READY = 'print("ready") io.stdout:flush()'

SCENE = two_pulley(elements=40)


class Stop(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_stop_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.procs = []

    def tearDown(self):
        for p in self.procs:
            if p.poll() is None:
                p.kill()
                p.wait()
            for stream in (p.stdin, p.stdout, p.stderr):
                if stream:
                    stream.close()

    def script(self, text):
        path = os.path.join(self.dir, "s.lua")
        with open(path, "w") as f:
            f.write(text)
        return path

    def start(self, args, stdin=None):
        env = dict(os.environ, GALLIUM_DRIVER=os.environ.get("GALLIUM_DRIVER", "llvmpipe"))
        p = subprocess.Popen([BELTSIM] + args, cwd=self.dir, env=env, stdin=subprocess.PIPE if stdin else None,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.procs.append(p)
        if stdin:
            p.stdin.write(stdin.encode())
            p.stdin.flush()
        return p

    def wait_line(self, stream, text, timeout=60):
        """reads stream until a line holding text comes; what was read"""
        seen, deadline = b"", time.monotonic() + timeout
        while text.encode() not in seen:
            left = deadline - time.monotonic()
            r, _, _ = select.select([stream], [], [], max(left, 0))
            if not r:
                self.fail("no %r within %.0f s; read %r" % (text, timeout, seen))
            chunk = os.read(stream.fileno(), 4096)
            if not chunk:
                self.fail("the stream ended before %r; read %r" % (text, seen))
            seen += chunk
        return seen.decode()

    def wait_rows(self, csv):
        """waits until csv holds some rows: the run is under way"""
        deadline = time.monotonic() + 60
        while os.path.getsize(csv) < 2000:
            self.assertLess(time.monotonic(), deadline, "the run wrote no rows")
            time.sleep(0.02)

    def ends(self, p, sig, err_so_far=""):
        """sends sig; the exit status and stderr once the process has ended (within LIMIT)"""
        t0 = time.monotonic()
        p.send_signal(sig)
        try:
            p.wait(timeout=LIMIT)
        except subprocess.TimeoutExpired:
            self.fail("still running %.0f s after %s" % (LIMIT, signal.Signals(sig).name))
        took = time.monotonic() - t0
        err = err_so_far + p.stderr.read().decode()
        print("  %s: ended in %.2f s, status %d" % (signal.Signals(sig).name, took, p.returncode), file=sys.stderr)
        return p.returncode, err

    # SIGTERM ends the process: the watchdog takes SIGTERM's own action (-15), or the host returns 143
    def assert_terminated(self, status, err):
        self.assertIn(status, (-signal.SIGTERM, 143), err)
        self.assertIn("terminated" if status == 143 else "did not stop within", err)

    def test_sigterm_ends_a_message_handler_that_loops(self):
        p = self.start(["run", self.script(READY + "\n" + HANDLER + "\n")])
        self.wait_line(p.stdout, "ready")
        self.assert_terminated(*self.ends(p, signal.SIGTERM))

    def test_sigterm_ends_a_long_pattern_match(self):
        p = self.start(["run", self.script(READY + "\n" + PATTERN + "\n")])
        self.wait_line(p.stdout, "ready")
        self.assert_terminated(*self.ends(p, signal.SIGTERM))

    def test_sigterm_ends_the_console_in_a_long_pattern_match(self):
        p = self.start(["console", "--out", "out"], stdin=READY + " " + PATTERN + "\n")  # one command
        self.wait_line(p.stdout, "ready")
        self.assert_terminated(*self.ends(p, signal.SIGTERM))

    def test_a_second_ctrl_c_ends_a_long_pattern_match(self):
        # the first Ctrl-C cannot stop a C call: the watchdog says so, and the second one ends beltsim
        for args, stdin in [(["run", self.script(READY + "\n" + PATTERN + "\n")], None),
                                  (["console", "--out", "out"], READY + " " + PATTERN + "\n")]:
            p = self.start(args, stdin=stdin)
            self.wait_line(p.stdout, "ready")
            p.send_signal(signal.SIGINT)
            err = self.wait_line(p.stderr, "Ctrl-C again ends beltsim")
            self.assertIsNone(p.poll(), err)
            status, err = self.ends(p, signal.SIGINT, err)
            self.assertEqual(status, -signal.SIGINT, err)

    def test_lua_after_a_stopped_run_stops(self):
        # run_to stops at a step end and Lua goes on (no "interrupted!" there); after SIGTERM the
        # loop that follows is interrupted too, and the outputs are closed: 143
        p = self.start(["run", self.script(
            SCENE + "sim = drive:start { progress = false, out = 'out' }\n" + READY + "\n"
            "sim:run_to(1000)\nwhile true do end\n")])
        self.wait_line(p.stdout, "ready")
        csv = os.path.join(self.dir, "out", "timeseries.csv")
        self.wait_rows(csv)
        status, err = self.ends(p, signal.SIGTERM)
        self.assertEqual(status, 143, err)
        self.assertIn("interrupted!", err)
        self.assertIn("beltsim: terminated; the outputs written so far are kept", err)
        with open(csv) as f:
            self.assertTrue(f.read().endswith("\n"))

    def test_no_run_starts_after_ctrl_c(self):
        # a script of two runs, Ctrl-C in the first: the script goes on (it may save what it has),
        # but the second run neither starts nor opens its folder, whose earlier result stays: 130
        second = os.path.join(self.dir, "second")
        os.makedirs(second)
        with open(os.path.join(second, "timeseries.csv"), "w") as f:
            f.write("t\n0\n0.001\n")  # an earlier result
        p = self.start(["run", self.script(
            SCENE + "sim = drive:start { progress = false, out = 'first' }\n" + READY + "\n"
            "local r = sim:run_to(1000)\n"
            "print('stopped', r.interrupted) io.stdout:flush()\n"
            "sim:save('stopped.ckpt')\n"
            "drive:run { t_end = 0.01, progress = false, out = 'second' }\n"
            "print('second run done')\n")])
        self.wait_line(p.stdout, "ready")
        csv = os.path.join(self.dir, "first", "timeseries.csv")
        self.wait_rows(csv)
        status, err = self.ends(p, signal.SIGINT)
        out = p.stdout.read().decode()
        self.assertEqual(status, 130, err)
        self.assertIn("stopped\ttrue", out)
        self.assertNotIn("second run done", out)
        self.assertTrue(os.path.exists(os.path.join(self.dir, "first", "stopped.ckpt")), err)
        self.assertIn("s.lua:%d: scene:run: not run: Ctrl-C (or SIGTERM) stopped a run earlier" % (SCENE.count("\n") + 6), err)
        with open(os.path.join(second, "timeseries.csv")) as f:
            self.assertEqual(f.read(), "t\n0\n0.001\n")

    def test_ctrl_c_in_a_callback_or_a_law_stops_the_run(self):
        # Lua code that a run calls (a live simulation's callback, a Lua torque law) and Ctrl-C
        # interrupts: the run stops there as Ctrl-C between its steps stops it, said by the run's
        # closing line, and parameters.csv says interrupted (a user's trial: "failed", "an error in a
        # callback", and no closing line), exit 130
        loop = 'print("looping") io.stdout:flush() while true do end'
        law = ("local function load(t, w)\n  if t > 0.01 then " + loop + " end\n  return -0.955 * w\nend\n" +
               SCENE.replace("torque = { per_speed = -0.955 }", "torque = load"))
        for name, text, at in [
                ("callback", SCENE + "sim = drive:start { out = 'out' }\n"
                 "sim:every(0.01, function(s) " + loop + " end)\nlocal r = sim:run_to(1)\n"
                 "print('returned', r.interrupted, r.t) io.stdout:flush()\nsim:close()\n", r"0\.01"),
                ("law", law + "drive:run { t_end = 1, out = 'out' }\n", r"0\.0[0-9]+")]:
            shutil.rmtree(os.path.join(self.dir, "out"), True)
            p = self.start(["run", self.script(text)])
            self.wait_line(p.stdout, "looping")
            status, err = self.ends(p, signal.SIGINT)
            out = p.stdout.read().decode()
            self.assertEqual(status, 130, name + ": " + err)
            self.assertRegex(err, r"beltsim: run stopped at t = %s s of 1 s \(\d+ steps, [0-9.]+ s\): out/\n" % at,
                             name)
            self.assertIn("beltsim: interrupted; the outputs written so far are kept\n", err, name)
            with open(os.path.join(self.dir, "out", "parameters.csv")) as f:
                end = [row for row in f.read().splitlines() if row.startswith("end.status,")]
            self.assertEqual(len(end), 1, name)
            self.assertTrue(end[0].startswith("end.status,interrupted,,derived,"), name + ": " + end[0])
            self.assertNotIn("error in a callback", end[0], name)
            if name == "callback":  # the script goes on after the stopped run, as after any stopped run
                self.assertIn("returned\ttrue\t0.01\n", out)

    def test_sighup_is_handled_as_sigterm(self):
        p = self.start(["run", self.script(
            SCENE + "drive:run { t_end = 3, progress = false, out = 'out', "
            "frames = { size = {320, 240}, video = 'v.mp4' } }\n")])
        frames = os.path.join(self.dir, "out", "frames")
        csv = os.path.join(self.dir, "out", "timeseries.csv")
        deadline = time.monotonic() + 60
        while not (os.path.exists(csv) and os.path.getsize(csv) > 2000):  # frames being made
            self.assertIsNone(p.poll(), p.stderr.read().decode() if p.poll() is not None else "")
            self.assertLess(time.monotonic(), deadline, "the run wrote no rows")
            time.sleep(0.02)
        status, err = self.ends(p, signal.SIGHUP)
        self.assertEqual(status, 129, err)
        self.assertIn("beltsim: hung up (SIGHUP); the outputs written so far are kept", err)
        video = os.path.join(self.dir, "out", "v.mp4")
        r = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames", "-of", "csv=p=0", video], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(re.match(r"\s*[1-9]\d*", r.stdout), r.stdout + r.stderr)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
