#!/usr/bin/env python3
"""`beltsim sweep` (docs/sweeps.md) through the program itself: the grid's order and ids, --list,
--point, a failing point among good ones, the --set cross form, the summary against the points
run one by one, resumption after a Ctrl-C and after a kill (only the points not done run again),
`beltsim plot` on a summary (errors after the points are known, --collect's refusals and a folder
in use: sweep_errors_test.py). Waits are for events (a point's point.csv, a file the test
writes), never fixed sleeps.

usage: sweep_test.py BELTSIM
"""
import csv
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

BELTSIM = None
HERE = os.path.dirname(os.path.abspath(__file__))
GRID = os.path.join(HERE, "grid.lua")
BAD = os.path.join(HERE, "bad_point.lua")
PLAIN = os.path.join(HERE, "plain.lua")
DRIVE = os.path.join(HERE, "drive.lua")  # the scene of every sweep here (require "drive")
LIMIT = 60.0
# points 0 (scene:run) and 2 (sim:run_to) of this sweep diverge at once (a torque of 1e12 N·m)
DIVERGES = """
local drive = require "drive"
return beltsim.sweep {
  grid = { how = {"run", "start"}, torque = {-1e12, 0} },
  run = function(p)
    local s = beltsim.scene(drive { torque = p.torque })
    if p.how == "run" then
      s:run { t_end = 0.01, sample = 1e-3, progress = false, max_wall = 60 }
    else
      local sim = s:start { sample = 1e-3, progress = false, max_wall = 60 }
      sim:run_to(0.01)
    end
  end,
}
"""  # [s] for one event; the points take a fraction of a second each



# a sweep whose driven pulley's damping is in the sweep file and its belt's mass in a module it
# loads (require): editing either changes every point's figures
EDITABLE = """
local belt = require "belt_params"
local drive = require "drive"
return beltsim.sweep {
  grid = { pretension = {300, 400, 500, 600} },
  run = function(p)
    local s = beltsim.scene(drive { pretension = p.pretension, per_speed = DAMPING, mass_per_length = belt.mass })
    local r = s:run { t_end = 0.02, sample = 1e-3, progress = false }
    return { slip = r.omega.driver - r.omega.driven, steps = r.steps }
  end,
}
"""


def alive(pid):
    """the process runs (not gone, not a zombie)"""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


class SweepCase(unittest.TestCase):
    """a test's own folder, beltsim run in it, waits (sweep_errors_test.py's tests too)"""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_sweep_")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def run_beltsim(self, *args, ok=(0,)):
        p = subprocess.run([BELTSIM, *args], cwd=self.dir, capture_output=True, text=True, timeout=300)
        self.assertIn(p.returncode, ok, p.stderr)
        return p

    def path(self, *parts):
        return os.path.join(self.dir, *parts)

    def read(self, *parts):
        with open(self.path(*parts), "rb") as f:
            return f.read()

    def wait_for(self, path, proc):
        end = time.monotonic() + LIMIT
        while not os.path.exists(path):
            self.assertIsNone(proc.poll(), "the sweep ended before " + path)
            self.assertLess(time.monotonic(), end, "no " + path)
            time.sleep(0.005)

    def point_process(self, proc, k):
        """the pid of the process of point k of the sweep proc, once it has started"""
        end = time.monotonic() + LIMIT
        while True:
            self.assertIsNone(proc.poll(), "the sweep ended before point %d started" % k)
            self.assertLess(time.monotonic(), end, "point %d never started" % k)
            with open("/proc/%d/task/%d/children" % (proc.pid, proc.pid)) as f:
                for c in f.read().split():
                    try:
                        with open("/proc/%s/cmdline" % c, "rb") as g:
                            if b"\0--point\0%d\0" % k in g.read():
                                return int(c)
                    except (FileNotFoundError, ProcessLookupError):  # the child ended meanwhile
                        pass
            time.sleep(0.005)

    def assert_counts_agree(self, stderr):
        """the sweep's last progress line counts what its closing line does: the results
        summary.csv holds"""
        lines = stderr.replace("\r", "\n").splitlines()
        progress = [m for m in map(re.compile(r"sweep \S+: (\d+)/(\d+) done, (\d+) failed(.*)$").match, lines) if m]
        closing = [m for m in map(re.compile(r"beltsim sweep: .*summary.csv: (\d+) ok, (\d+) failed, (\d+) not run "
                                             r"\(the results it holds of the (\d+) points, whenever they ran\)$").match,
                                  lines) if m]
        self.assertTrue(progress and len(closing) == 1, stderr)
        done, total, failed, rest = progress[-1].groups()
        self.assertEqual(rest, "", stderr)  # nothing running, no estimate
        ok, failed_now, not_run, points = closing[0].groups()
        self.assertEqual((done, failed, total), (ok, failed_now, points), stderr)
        self.assertEqual(int(ok) + int(failed_now) + int(not_run), int(points), stderr)
        return int(ok), int(failed_now), int(not_run)


class Sweep(SweepCase):
    def test_grid_order_and_ids(self):
        # names in alphabetical order, the last varying fastest; ids 0..n-1
        out = self.run_beltsim("sweep", GRID, "--list").stdout.splitlines()
        self.assertEqual(out, ["point,mu,pretension", "0,0.3,300", "1,0.3,500", "2,0.6,300", "3,0.6,500",
                               "4,1,300", "5,1,500"])
        self.assertFalse(os.path.exists(self.path("out")), "--list ran something")

    def test_a_bad_grid_list_is_reported_at_its_line(self):
        # an empty list as a bad value in it: at the list's line, spelt sweep.grid.NAME (trial 16:
        # an empty one was "d5.lua:1: sweep: grid.load: no values", the line of beltsim.sweep's call)
        script = self.path("badgrid.lua")
        for load, expect in [("{}", ":4: sweep.grid.load: no values"),
                             ("{-0.1, {1}}", ":4: sweep.grid.load[2]: a number, string or boolean expected, got table")]:
            with open(script, "w") as f:
                f.write("return beltsim.sweep {\n  grid = {\n    pretension = {200, 300},\n    load = %s,\n  },\n"
                        "  run = function(p) return { x = p.load + p.pretension } end,\n}\n" % load)
            p = self.run_beltsim("sweep", script, "--list", ok=(1,))
            self.assertIn(script + expect, p.stderr)

    def test_summary_matches_the_points_run_one_by_one(self):
        self.run_beltsim("sweep", GRID, "--jobs", "2")
        summary = rows(self.path("out", "grid", "summary.csv"))
        self.assertEqual(summary[0][:4], ["point", "mu", "pretension", "status"])
        self.assertEqual(len(summary), 7)
        self.assertTrue(all(r[3] == "ok" for r in summary[1:]), summary)
        self.assertIn("slip", summary[0])
        # each point alone, in this process, into another folder, then merged
        for k in range(6):
            self.run_beltsim("sweep", GRID, "--point", str(k), "--out", "alone")
        self.run_beltsim("sweep", GRID, "--collect", "--out", "alone")
        self.assertEqual(rows(self.path("alone", "summary.csv")), summary)
        # full precision: each figure reads back as the point's own value
        for r in summary[1:]:
            point = dict(zip(*rows(self.path("out", "grid", r[0], "point.csv"))))
            self.assertIn(GRID, point.pop("inputs"))
            self.assertEqual(dict(zip(summary[0], r)), point)
        slip = [float(r[summary[0].index("slip")]) for r in summary[1:]]
        self.assertEqual(len(set(slip)), 6, "the points gave the same figures")

    def test_one_point(self):
        p = self.run_beltsim("sweep", GRID, "--point", "4")
        self.assertEqual(sorted(os.listdir(self.path("out", "grid"))), ["4"])
        point = rows(self.path("out", "grid", "4", "point.csv"))
        self.assertEqual(point[1][:4], ["4", "1", "300", "ok"])
        self.assertTrue(os.path.exists(self.path("out", "grid", "4", "timeseries.csv")))
        self.assertIn("point 4: ok", p.stderr)
        p = self.run_beltsim("sweep", GRID, "--point", "6", ok=(2,))
        self.assertIn("points 0..5", p.stderr)

    def test_a_failing_point_does_not_stop_the_others(self):
        p = self.run_beltsim("sweep", BAD, "--jobs", "1", ok=(1,))
        summary = rows(self.path("out", "bad_point", "summary.csv"))
        status = [r[2] for r in summary[1:]]
        self.assertEqual(status[0], "ok")
        self.assertEqual(status[2], "ok")
        self.assertTrue(status[1].startswith("error: " + BAD + ":"), status[1])
        self.assertIn("belt.mu must be in [0, 10]", status[1])
        self.assertEqual(summary[2][3], "")  # no figure for the failed point
        self.assertIn("point 1 (mu=-1): error:", p.stderr)
        # run again: only the failed point runs
        p = self.run_beltsim("sweep", BAD, ok=(1,))
        self.assertIn("2 of 3 points done already", p.stderr)

    def test_a_diverged_point_says_when(self):
        script = self.path("div.lua")
        with open(script, "w") as f:
            f.write(DIVERGES)
        shutil.copy(DRIVE, self.dir)
        for k in (0, 2):
            p = self.run_beltsim("sweep", script, "--point", str(k), ok=(1,))
            status = rows(self.path("out", "div", str(k), "point.csv"))[1][3]
            # the time, then the whole message (it said the time alone): file:line, the cause, the samples
            run = r" \(the samples up to then are in out/div/0/timeseries.csv\)" if k == 0 else ""
            self.assertRegex(status, r"^diverged at t = [0-9.e+-]+ s: %s:[0-9]+: (sim:run_to: )?pulley 'driver' "
                                     r"runs away at -?[0-9.e+]+ rad/s in the step to t = [0-9.e+-]+ s%s$"
                                     % (re.escape(script), run))
            self.assertNotIn("the run diverged", status)
            if k == 0:  # one stop time: the status's is the run's end.t, exactly (trial 16: 0.2 ms apart)
                end = {r[0]: r[1] for r in rows(self.path("out", "div", "0", "parameters.csv"))}
                self.assertEqual(status[len("diverged at t = "):status.index(" s: ")], end["end.t"])
            self.assertIn("point %d: %s\n" % (k, status), p.stderr)  # (its log.txt in a sweep)

    def test_samples_are_listed_in_their_ranges(self):
        script = self.path("samples.lua")
        with open(script, "w") as f:
            f.write("return beltsim.sweep { samples = { n = 12, seed = 7, ranges = { mu = {0.2, 0.8} } },"
                    " run = function(p) return { twice = 2 * p.mu } end }\n")
        out = self.run_beltsim("sweep", script, "--list").stdout.splitlines()
        self.assertEqual(out[0], "point,mu")
        self.assertEqual([r.split(",")[0] for r in out[1:]], ["%02d" % k for k in range(12)])
        mu = [float(r.split(",")[1]) for r in out[1:]]
        self.assertTrue(all(0.2 <= m < 0.8 for m in mu), mu)
        self.assertEqual(out, self.run_beltsim("sweep", script, "--list").stdout.splitlines())
        self.run_beltsim("sweep", script, "--jobs", "2")
        summary = rows(self.path("out", "samples", "summary.csv"))
        self.assertEqual([float(r[3]) for r in summary[1:]], [2 * m for m in mu])
        # a mistake in the sweep names its line
        with open(script, "w") as f:
            f.write("return beltsim.sweep {\n  samples = { n = 0, ranges = { mu = {0.2, 0.8} } },\n"
                    "  run = function(p) end }\n")
        p = self.run_beltsim("sweep", script, "--list", ok=(1,))
        self.assertIn(script + ":2: sweep.samples.n: must be a whole number in 1..1000000 (got 0)", p.stderr)
        # a value of the wrong type: the line of its key, and the value
        with open(script, "w") as f:
            f.write("return beltsim.sweep {\n  samples = {\n    n = 2.5,\n    ranges = { mu = {0.2, 0.8} } },\n"
                    "  run = function(p) end }\n")
        p = self.run_beltsim("sweep", script, "--list", ok=(1,))
        self.assertIn(script + ":3: sweep.samples.n: a whole number expected, got number 2.5", p.stderr)
        with open(script, "w") as f:  # a float of whole value, as Lua writes it: no integer
            f.write("return beltsim.sweep { samples = { n = 6 / 2, ranges = { mu = {0.2, 0.8} } }, run = function(p) end }\n")
        p = self.run_beltsim("sweep", script, "--list", ok=(1,))
        self.assertIn("sweep.samples.n: a whole number expected, got number 3.0", p.stderr)

    def test_set_lists_cross_over_a_script(self):
        self.run_beltsim("sweep", PLAIN, "--set", "pretension=300,500", "--set", "mu=0.3,1")
        summary = rows(self.path("out", "plain", "summary.csv"))
        self.assertEqual(summary[0][:4], ["point", "pretension", "mu", "status"])
        self.assertEqual([r[:4] for r in summary[1:]], [["0", "300", "0.3", "ok"], ["1", "300", "1", "ok"],
                                                        ["2", "500", "0.3", "ok"], ["3", "500", "1", "ok"]])
        self.assertIn("omega.driver", summary[0])  # the result table of the script's run
        # its units from the program's table (they came from brackets alone: omega.driver had none)
        units = dict(rows(self.path("out", "plain", "summary_units.csv"))[1:])
        self.assertEqual(list(units), summary[0])
        self.assertEqual(units, {"point": "", "pretension": "", "mu": "", "status": "", "csv": "",
                                 "factorizations": "1", "frames": "1", "interrupted": "", "jacobians": "1",
                                 "omega.driven": "rad/s", "omega.driver": "rad/s", "parameters": "", "rejected": "1",
                                 "rhs": "1", "steps": "1", "t": "s", "wall": "s"})
        # a point is the script run with those values
        self.run_beltsim("run", PLAIN, "--set", "pretension=500", "--set", "mu=0.3", "--out", "direct")
        with open(self.path("direct", "timeseries.csv")) as a, open(self.path("out", "plain", "2", "timeseries.csv")) as b:
            self.assertEqual(a.read(), b.read())
        p = self.run_beltsim("sweep", PLAIN, "--set", "mu=0.3,1x", ok=(2,))  # a number's typo
        self.assertIn("1x", p.stderr)
        # an empty item (300,,500; a trailing comma) before anything runs, where its point failed
        # when its run read the empty string
        for bad in ("pretension=300,,500", "pretension=300,"):
            p = self.run_beltsim("sweep", PLAIN, "--set", bad, ok=(2,))
            self.assertIn("--set %s: an empty value in the list (write \"\" for an empty string)" % bad, p.stderr)
        self.assertEqual(self.run_beltsim("sweep", PLAIN, "--set", 'how="",a', "--list").stdout.splitlines()[1], "0,")

    def test_set_lists_on_a_sweep_file_are_refused_before_anything_is_written(self):
        # each point failed ("is a sweep file"), and a finished sweep's summary.csv and point.csv
        # were replaced by errors
        script = self.path("twice.lua")
        with open(script, "w") as f:
            f.write("return beltsim.sweep { grid = { mu = {0.3, 1} }, run = function(p) return { twice = 2 * p.mu } end }\n")
        self.run_beltsim("sweep", script, "--jobs", "1")
        before = {name: self.read("out", "twice", *name) for name in (("summary.csv",), ("0", "point.csv"))}
        # --list printed the --set lists' points, and --point 0 replaced point 0's point.csv with an error
        for out in ([], ["--out", "elsewhere"], ["--slurm"], ["--list"], ["--point", "0"]):
            p = self.run_beltsim("sweep", script, "--set", "mu=0.3,1", *out, ok=(2,))
            self.assertIn("beltsim: %s is a sweep file (it returns beltsim.sweep{...}): its points are its grid or "
                          "samples; --set lists are for an ordinary script (the quick form): run `beltsim sweep %s` "
                          "without them\n" % (script, script), p.stderr)
            self.assertEqual(p.stdout, "")
        self.assertEqual({name: self.read("out", "twice", *name) for name in before}, before)
        self.assertEqual(sorted(os.listdir(self.path("out", "twice"))), ["0", "1", "summary.csv", "summary_units.csv"])
        self.assertFalse(os.path.exists(self.path("elsewhere")))
        # what an ordinary script prints before its first scene:run (run to tell it from a sweep
        # file) is not among --list's rows
        shutil.copy(DRIVE, self.dir)
        with open(PLAIN) as f, open(self.path("talks.lua"), "w") as g:
            g.write("print('mu is', beltsim.args.mu)\n" + f.read())
        p = self.run_beltsim("sweep", "talks.lua", "--set", "mu=0.3,1", "--set", "pretension=500", "--list")
        self.assertEqual(p.stdout, "point,mu,pretension\n0,0.3,500\n1,1,500\n")
        self.assertIn("mu is\t0.3\n", p.stderr)

    def test_an_ordinary_script_without_set_lists_is_refused_before_it_runs(self):
        # it ran whole, into out/<script> whatever --out said, and was refused after
        for args in (["--out", "there"], ["--list"], ["--slurm"]):
            p = self.run_beltsim("sweep", PLAIN, *args, ok=(2,))
            self.assertIn("beltsim: %s:4: scene:run: %s runs a simulation as it loads: it is an ordinary script, not a "
                          "sweep file (which returns beltsim.sweep{...} and runs its simulations in run(p)); nothing "
                          "was run. For a study of it, give its parameters as --set lists: beltsim sweep %s --set "
                          "NAME=V1,V2,..\n" % (PLAIN, PLAIN, PLAIN), p.stderr)
            self.assertEqual(p.stdout, "")
        script = self.path("start.lua")
        with open(script, "w") as f:
            f.write("local drive = require 'drive'\nlocal s = beltsim.scene(drive {})\n"
                    "local sim = s:start { sample = 1e-3, progress = false }\nsim:run_to(0.01)\n")
        shutil.copy(DRIVE, self.dir)
        p = self.run_beltsim("sweep", script, ok=(2,))
        self.assertIn("beltsim: %s:3: scene:start: %s runs a simulation as it loads" % (script, script), p.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["drive.lua", "start.lua"])

    def test_a_quoted_set_value_keeps_its_commas(self):
        # "..." around a value of a --set list, as --set reads a string: its commas are its own
        out = self.run_beltsim("sweep", PLAIN, "--set", 'how="a,b",c,"d"', "--set", 'x="1,2"', "--list").stdout
        self.assertEqual(list(csv.reader(out.splitlines())), [["point", "how", "x"], ["0", "a,b", "1,2"],
                                                             ["1", "c", "1,2"], ["2", "d", "1,2"]])
        for bad in ('how="a,b', 'how=a,"b', 'how="a"b,c'):
            p = self.run_beltsim("sweep", PLAIN, "--set", bad, "--list", ok=(2,))
            self.assertIn("--set " + bad, p.stderr)
            self.assertIn("quote", p.stderr)

    def test_values_read_back_exactly_and_columns_are_named_once(self):
        # strings with \r, \n, commas and quotes, as parameters and figures: summary.csv holds them
        # exactly, and each point.csv reads back (the next sweep finds every point done)
        script = self.path("odd.lua")
        with open(script, "w") as f:
            f.write('return beltsim.sweep { grid = { how = {"a\\rb", "c\\nd", "e,\\"f\\""} },\n'
                    '  run = function(p) return { echo = p.how .. "\\r\\n!" } end }\n')
        self.run_beltsim("sweep", script, "--jobs", "1")
        self.assertEqual(rows(self.path("out", "odd", "summary.csv")), [
            ["point", "how", "status", "echo"], ["0", "a\rb", "ok", "a\rb\r\n!"], ["1", "c\nd", "ok", "c\nd\r\n!"],
            ["2", 'e,"f"', "ok", 'e,"f"\r\n!']])
        p = self.run_beltsim("sweep", script)
        self.assertIn("3 of 3 points done already", p.stderr)
        # a parameter named as another column is refused; a point whose figure is, fails saying so
        with open(script, "w") as f:
            f.write("return beltsim.sweep { grid = { status = {1} }, run = function(p) end }\n")
        p = self.run_beltsim("sweep", script, "--list", ok=(1,))
        self.assertIn("status", p.stderr)
        p = self.run_beltsim("sweep", PLAIN, "--set", "point=1,2", "--list", ok=(2,))
        self.assertIn("--set point=1,2", p.stderr)
        with open(script, "w") as f:
            f.write("return beltsim.sweep { grid = { k = {1} }, run = function(p) return { k = p.k, status = 3 } end }\n")
        self.run_beltsim("sweep", script, ok=(1,))
        summary = rows(self.path("out", "odd", "summary.csv"))
        self.assertEqual(summary[0], ["point", "k", "status"])
        self.assertTrue(summary[1][2].startswith("error: ") and "'k'" in summary[1][2], summary[1][2])

    def test_a_parameter_misspelt_or_never_read_fails_the_point(self):
        # p.pretension read where the grid says pretention was nil, the scene's default for every
        # point, each ok; a parameter run(p) never reads decided nothing either
        script = self.path("typo.lua")
        with open(script, "w") as f:
            f.write("return beltsim.sweep {\n"
                    "  grid = { pretention = {300, 600}, mu = {1} },\n"
                    "  run = function(p)\n"
                    "    return { mu = p.mu, f = p.pretension }\n"
                    "  end,\n"
                    "}\n")
        p = self.run_beltsim("sweep", script, "--jobs", "1", ok=(1,))
        status = [r[3] for r in rows(self.path("out", "typo", "summary.csv"))[1:]]
        self.assertEqual(status, ["error: %s:4: p.pretension: the point has no parameter 'pretension' (did you mean "
                                  "'pretention'?); its parameters: mu, pretention" % script] * 2)
        self.assertIn("point 0 (mu=1, pretention=300): error: ", p.stderr)
        with open(script, "w") as f:
            f.write("return beltsim.sweep { grid = { a = {1, 2}, b = {'x'} }, run = function(p)\n"
                    "  return { twice = 2 * p.a } end }\n")
        self.run_beltsim("sweep", script, "--jobs", "1", ok=(1,))
        status = [r[3] for r in rows(self.path("out", "typo", "summary.csv"))[1:]]
        self.assertEqual(status, ["error: %s: run(p) never read p.b: a parameter that decides nothing makes points "
                                  "that differ in name only; read it in run(p), or take it out of the sweep" % script] * 2)
        # pairs(p) lists the parameters (each read so); a key run(p) sets is its own
        with open(script, "w") as f:
            f.write("return beltsim.sweep { grid = { a = {1, 2}, b = {'x'} }, run = function(p)\n"
                    "  local s = {}\n"
                    "  for k, v in pairs(p) do s[#s + 1] = k .. '=' .. tostring(v) end\n"
                    "  table.sort(s)\n"
                    "  p.c = 3\n"
                    "  return { all = table.concat(s, ';'), c = p.c } end }\n")
        self.run_beltsim("sweep", script, "--jobs", "1")
        self.assertEqual(rows(self.path("out", "typo", "summary.csv")),
                         [["point", "a", "b", "status", "all", "c"], ["0", "1", "x", "ok", "a=1;b=x", "3"],
                          ["1", "2", "x", "ok", "a=2;b=x", "3"]])

    def test_a_run_that_returns_nothing_fails_and_an_empty_table_is_said(self):
        # a run(p) that forgot its return was ok with no figures, without a word
        script = self.path("none.lua")
        with open(script, "w") as f:
            f.write("return beltsim.sweep {\n  grid = { k = {1, 2} },\n  run = function(p)\n"
                    "    local twice = 2 * p.k\n  end,\n}\n")
        p = self.run_beltsim("sweep", script, "--jobs", "1", ok=(1,))
        self.assertEqual([r[2] for r in rows(self.path("out", "none", "summary.csv"))[1:]],
                         ["error: %s:3: run(p) returned nil; return a table of figures" % script] * 2)
        with open(script, "w") as f:
            f.write("return beltsim.sweep { grid = { k = {1, 2} }, run = function(p) local _ = p.k return {} end }\n")
        p = self.run_beltsim("sweep", script, "--jobs", "1")
        self.assertEqual(rows(self.path("out", "none", "summary.csv")), [["point", "k", "status"], ["0", "1", "ok"],
                                                                        ["1", "2", "ok"]])
        warning = ("sweep none: warning: point 0 (k=1) is ok with no figures: run(p) returned an empty table (said of "
                   "the first such point only)\n")
        self.assertIn(warning, p.stderr)
        self.assertEqual(p.stderr.count("with no figures"), 1, p.stderr)

    def write_editable(self, damping, mass):
        shutil.copy(DRIVE, self.dir)
        with open(self.path("editable.lua"), "w") as f:
            f.write(EDITABLE.replace("DAMPING", damping))
        with open(self.path("belt_params.lua"), "w") as f:
            f.write("return { mass = %s }\n" % mass)  # kg/m: the belt's mass per length

    def test_a_resumed_sweep_after_an_edit_equals_an_uninterrupted_one(self):
        # a sweep stopped after its first point, a file that defines it edited, the same command
        # again: its summary.csv is byte for byte that of the edited sweep run whole elsewhere
        for n, edit in enumerate((("-0.7", "0.096"), ("-0.5", "0.11"))):  # the sweep file, the module it loads
            with self.subTest(edit=edit):
                resumed, whole = "resumed%d" % n, "whole%d" % n
                self.write_editable("-0.5", "0.096")
                args = ["sweep", "editable.lua", "--jobs", "1", "--out", resumed]
                proc = subprocess.Popen([BELTSIM, *args], cwd=self.dir, stderr=subprocess.PIPE, text=True)
                self.wait_for(self.path(resumed, "0", "point.csv"), proc)
                proc.send_signal(signal.SIGINT)
                proc.communicate(timeout=LIMIT)
                self.write_editable(*edit)
                p = self.run_beltsim(*args)
                self.run_beltsim("sweep", "editable.lua", "--jobs", "2", "--out", whole)
                self.assertEqual(self.read(resumed, "summary.csv"), self.read(whole, "summary.csv"))
                changed = self.path("editable.lua" if edit[0] != "-0.5" else "belt_params.lua")
                self.assertRegex(p.stderr, r"sweep editable: [1-4] points? runs? again: the file %s has changed"
                                 % changed)
                self.assertNotIn("done already", p.stderr)

    def test_what_else_defines_a_point_reruns_it(self):
        # the same sweep file: an edit that changes nothing of its text keeps every point; another
        # program (the executable with a byte added, which runs the same), --trusted and --rerun
        # run them all again, saying why
        self.write_editable("-0.5", "0.096")
        self.run_beltsim("sweep", "editable.lua", "--jobs", "2")
        os.utime(self.path("editable.lua"))
        p = self.run_beltsim("sweep", "editable.lua", "--jobs", "2")
        self.assertIn("4 of 4 points done already", p.stderr)
        other = self.path("beltsim-copy")
        shutil.copy(BELTSIM, other)
        with open(other, "ab") as f:
            f.write(b"\0")
        p = subprocess.run([other, "sweep", "editable.lua", "--jobs", "2"], cwd=self.dir, capture_output=True,
                           text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("4 points run again: the program has changed", p.stderr)
        p = self.run_beltsim("sweep", "editable.lua", "--jobs", "2", "--trusted")
        self.assertIn("4 points run again: the program has changed", p.stderr)  # back to this one
        p = self.run_beltsim("sweep", "editable.lua", "--jobs", "2")
        self.assertIn("4 points run again: the options have changed (were '--trusted', now '')", p.stderr)
        p = self.run_beltsim("sweep", "editable.lua", "--jobs", "2", "--rerun")
        self.assertIn("--rerun: all 4 points run again", p.stderr)
        # an edited copy of the sweep file run into the same folder: not the points' sweep file
        with open(self.path("editable.lua")) as f, open(self.path("copy.lua"), "w") as g:
            g.write(f.read().replace("-0.5", "-0.7"))
        p = self.run_beltsim("sweep", "copy.lua", "--jobs", "2", "--out", "out/editable")
        self.assertIn("4 points run again: the sweep file has changed (was %s, now %s)"
                      % (self.path("editable.lua"), self.path("copy.lua")), p.stderr)
        p = self.run_beltsim("sweep", "editable.lua", "--jobs", "2")
        self.assertIn("4 points run again: the sweep file has changed", p.stderr)
        # the same file by another path (a symlinked folder): done already
        os.symlink(self.dir, self.path("link"))
        p = self.run_beltsim("sweep", "link/editable.lua", "--jobs", "2", "--out", "out/editable")
        self.assertIn("4 of 4 points done already", p.stderr)
        # --collect after an edit: the points are not the sweep's any more
        self.write_editable("-0.7", "0.096")
        self.run_beltsim("sweep", "editable.lua", "--collect", ok=(1,))
        summary = rows(self.path("out", "editable", "summary.csv"))
        self.assertEqual(summary[0], ["point", "pretension", "status"])
        for r in summary[1:]:
            self.assertEqual(r[2], "outdated: the file %s has changed" % self.path("editable.lua"))

    def test_a_value_added_to_a_set_list_runs_that_point_alone(self):
        # the --set lists are the grid, not what defines a point: its values are its parameters
        self.run_beltsim("sweep", PLAIN, "--set", "pretension=300,500")
        p = self.run_beltsim("sweep", PLAIN, "--set", "pretension=300,500,700")
        self.assertIn("2 of 3 points done already", p.stderr)
        self.assertNotIn("run again", p.stderr)

    def test_a_quick_study_of_other_parameters_is_refused_its_folder(self):
        # out/<script> is every quick study's of the script: one of other --set names replaced the
        # earlier study's summary.csv and points without a word
        # (--point K, as the sweep's points run or by hand, replaced point K's folder)
        self.run_beltsim("sweep", PLAIN, "--set", "pretension=300,500")
        files = ("summary.csv",), ("0", "point.csv"), ("0", "timeseries.csv")
        before = {f: self.read("out", "plain", *f) for f in files}
        for lists in (["--set", "mu=0.3,1"], ["--set", "pretension=300,500", "--set", "mu=0.3,1"]):
            for point in ([], ["--point", "0"]):
                p = self.run_beltsim("sweep", PLAIN, *lists, *point, ok=(1,))
                self.assertIn("beltsim: out/plain holds another study (its points vary pretension, these vary %s), "
                              "whose summary.csv and points this one would replace: give it a folder of its own "
                              "(--out DIR), or remove out/plain first\n" % ("mu" if len(lists) == 2 else "pretension, mu"),
                              p.stderr)
                self.assertEqual({f: self.read("out", "plain", *f) for f in files}, before)
        self.run_beltsim("sweep", PLAIN, "--set", "mu=0.3,1", "--out", "out/plain_mu")
        self.assertEqual(rows(self.path("out", "plain_mu", "summary.csv"))[0][:3], ["point", "mu", "status"])

    def test_points_numbered_otherwise_run_again_saying_why(self):
        # a point's folder is its number: a value added inside a list, or ids widened (0..5 to
        # 00..11), renumbers points, which ran again without a word, and left the old folders
        # beside the new ones
        args = ["sweep", PLAIN, "--jobs", "2", "--set", "pretension=300,500"]
        self.run_beltsim(*args, "--set", "mu=0.3,1")
        p = self.run_beltsim(*args, "--set", "mu=0.3,0.5,1")
        self.assertIn("sweep plain: 3 points run again: the points were numbered otherwise when they ran (a value "
                      "added or removed before them in a list, or wider ids); a point's files name its folder, so its "
                      "results are not moved to its new number\n", p.stderr)
        self.assertIn("1 of 6 points done already", p.stderr)
        p = self.run_beltsim("sweep", PLAIN, "--jobs", "2", "--set", "pretension=300,500,700,900", "--set", "mu=0.3,0.5,1")
        self.assertIn("sweep plain: 6 points run again: the points were numbered otherwise", p.stderr)
        self.assertIn("sweep plain: 6 folders of no point now moved to out/plain/earlier/: 0, 1, 2, 3, 4, 5\n", p.stderr)
        self.assertEqual(sorted(os.listdir(self.path("out", "plain"))),
                         ["%02d" % k for k in range(12)] + ["earlier", "summary.csv", "summary_units.csv"])
        self.assertEqual([r[3] for r in rows(self.path("out", "plain", "summary.csv"))[1:]], ["ok"] * 12)
        # a moved folder's point.csv and parameters.csv name it where it lies now, not out/plain/1,
        # where it ran (and where another point's files may lie later)
        moved = dict(zip(*rows(self.path("out", "plain", "earlier", "1", "point.csv"))))
        self.assertEqual((moved["point"], moved["pretension"], moved["mu"]), ("1", "300", "0.5"))
        self.assertEqual((moved["csv"], moved["parameters"]), ("out/plain/earlier/1/timeseries.csv",
                                                              "out/plain/earlier/1/parameters.csv"))
        self.assertIn(["run.out", "out/plain/earlier/1", "", "run", "the output folder"],
                      rows(self.path("out", "plain", "earlier", "1", "parameters.csv")))

    def test_slurm_with_nothing_left_leaves_the_job_scripts(self):
        # --slurm --time, the points then run (here, as the array's tasks would), --slurm again
        self.run_beltsim("sweep", GRID, "--slurm", "--time", "10")
        before = self.read("out", "grid", "sweep.sbatch")
        self.assertIn(b"#SBATCH --array=0-5\n", before)
        self.run_beltsim("sweep", GRID, "--jobs", "2")
        p = self.run_beltsim("sweep", GRID, "--slurm")
        self.assertIn("nothing to submit", p.stderr)
        self.assertEqual(p.stdout, "")
        self.assertEqual(self.read("out", "grid", "sweep.sbatch"), before)
        # the sweep from an edited copy, into the same folder: every point in the array again (the
        # job scripts rewritten, with this --time), saying why as a local run does
        with open(GRID) as f, open(self.path("grid.lua"), "w") as g:
            g.write(f.read().replace("mu = p.mu", "mu = 0.9 * p.mu"))
        shutil.copy(DRIVE, self.dir)
        p = self.run_beltsim("sweep", "grid.lua", "--out", "out/grid", "--slurm", "--time", "20")
        after = self.read("out", "grid", "sweep.sbatch")
        self.assertIn(b"#SBATCH --array=0-5\n", after)
        self.assertIn(b"#SBATCH --time=20\n", after)
        self.assertIn("sweep grid: 6 points run again: the sweep file has changed (was %s, now %s)"
                      % (GRID, self.path("grid.lua")), p.stderr)
        # an edit of the file it loads: the reason named too
        with open(self.path("drive.lua"), "a") as f:
            f.write("-- edited\n")
        self.run_beltsim("sweep", "grid.lua", "--out", "out/grid", "--jobs", "2")
        with open(self.path("drive.lua"), "a") as f:
            f.write("-- edited again\n")
        p = self.run_beltsim("sweep", "grid.lua", "--out", "out/grid", "--slurm")
        self.assertIn("sweep grid: 6 points run again: the file %s has changed" % self.path("drive.lua"), p.stderr)

    def finished_points(self):
        return [k for k in range(4) if os.path.exists(self.path("out", "plain", str(k), "point.csv"))]

    def interrupted_then_resumed(self, stop):
        # four points of 0.2 s each, one at a time: the sweep is stopped while point 1 runs or soon
        # after, and the rest run when it resumes
        args = [BELTSIM, "sweep", PLAIN, "--jobs", "1", "--set", "pretension=300,600", "--set", "mu=0.3,1",
                "--set", "t_end=0.2"]
        proc = subprocess.Popen(args, cwd=self.dir, stderr=subprocess.PIPE, text=True)
        first = self.path("out", "plain", "0", "point.csv")
        self.wait_for(first, proc)
        stop(proc)
        _, err = proc.communicate(timeout=LIMIT)
        before = os.stat(first).st_ino
        done = self.finished_points()
        if proc.returncode != -signal.SIGKILL:  # (killed outright, it says nothing)
            self.assertEqual(self.assert_counts_agree(err), (len(done), 0, 4 - len(done)))
        # summary.csv as the points stood when the sweep ended, however it ended
        summary = rows(self.path("out", "plain", "summary.csv"))
        self.assertEqual([k for k in range(4) if summary[k + 1][4] == "ok"], done)
        self.assertEqual([r[4] for r in summary[1:] if r[4] != "ok"], ["not run"] * (4 - len(done)))
        p = self.run_beltsim(*args[1:])
        self.assertIn("%d of 4 points done already" % len(done), p.stderr)
        self.assertEqual(os.stat(first).st_ino, before, "a finished point ran again")
        # the summary of the sweep run whole (in a folder of its own, so that the paths among the
        # figures are the same), every cell but the wall time
        os.mkdir(self.path("whole"))
        p = subprocess.run(args, cwd=self.path("whole"), capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr)
        resumed, whole = rows(self.path("out", "plain", "summary.csv")), rows(self.path("whole", "out", "plain",
                                                                                         "summary.csv"))
        wall = whole[0].index("wall")
        self.assertEqual([r[:wall] + r[wall + 1:] for r in resumed], [r[:wall] + r[wall + 1:] for r in whole])
        return proc.returncode

    def test_ctrl_c_stops_cleanly_and_the_rest_runs_later(self):
        status = self.interrupted_then_resumed(lambda p: p.send_signal(signal.SIGINT))
        self.assertEqual(status, 130)

    def test_a_killed_sweep_resumes(self):
        children = []

        def kill(proc):
            # the sweep without warning, once point 1 runs: that point gets SIGTERM and ends too
            children.append(self.point_process(proc, 1))
            proc.kill()
            finished = self.finished_points()
            for c in children:
                end = time.monotonic() + LIMIT
                while alive(c):
                    self.assertLess(time.monotonic(), end, "point process %d outlived the sweep" % c)
                    time.sleep(0.005)
            # stopped, not run to its end as an orphan
            self.assertEqual(self.finished_points(), finished)
        self.assertEqual(self.interrupted_then_resumed(kill), -signal.SIGKILL)
        self.assertTrue(children, "no point was running when the sweep was killed")

    def test_the_time_left_comes_from_points_that_ran_to_their_end(self):
        # point 0 fails at once (a negative mu): its time is no basis for the others', which take
        # longer, so no estimate is given until a point has run to its end ("about 0 s left")
        p = self.run_beltsim("sweep", PLAIN, "--jobs", "2", "--set", "mu=-1,0.3,0.6", "--set", "t_end=0.3", ok=(1,))
        line = re.compile(r"sweep plain: (\d+)/3 done, (\d+) failed.*?(, about .* left)?$")
        lines = [m.groups() for m in map(line.match, p.stderr.splitlines()) if m]
        self.assertIn(("0", "1", None), lines, p.stderr)
        self.assertEqual([g for g in lines if g[0] == "0" and g[2]], [], p.stderr)
        self.assertEqual(self.assert_counts_agree(p.stderr), (2, 1, 0))

    def test_plot_of_a_summary(self):
        self.run_beltsim("sweep", GRID)
        p = self.run_beltsim("plot", "out/grid/summary.csv", "pretension", "slip", "steps")
        png = self.path("out", "grid", "plot.png")
        self.assertEqual(p.stdout.strip(), "out/grid/plot.png")
        self.assertGreater(os.path.getsize(png), 5000)
        p = self.run_beltsim("plot", "out/grid/summary.csv", "pretension", ok=(1,))
        self.assertIn("name the x column", p.stderr)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
