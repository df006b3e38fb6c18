#!/usr/bin/env python3
"""The time limits of each call into Lua through the program (docs/limits-and-safety.md; issue 45
§4): every form of long C-level work found by the hardening round stops with a message naming the
limit: in the process where Lua can stop it (table.move over 2^62, collections; string.rep of 128
MB in a loop and upper() of a 128 MB string as soon as the C call under way returns), by ending the
process where a C function cannot be stopped (string patterns that backtrack, a read that waits); a read that waits ends at the wall-time
limit, not the CPU-time one; a sweep point that hits a limit is recorded as failed with the reason.
The only bound on time is BOUND, far past what any case takes (a few seconds).

The cases whose work always outlasts the limit (every pattern and long C call) set it to SHORT, 0.1 s:
what they check (the limit reached and named, the process ended or the call stopped) does not
depend on its value, and each of their 14 runs spends the limit in CPU time before that (0.1 s
instead of 0.5: time_limits took 22.3 s of CPU, 17.9 s with it); 0.1 s is still 10 of the clock's
10 ms looks. The sweep keeps 0.5 s, since its first point must finish within it; the read that
waits keeps 0.5 s, above its CPU-time limit of 0.2 s, and uses no CPU time while it waits.

usage: time_limits_test.py BELTSIM
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

BELTSIM = None
BOUND = 120  # [s] a case that has not ended by then hangs

SHORT = "0.1"  # [s] --max-lua-wall of the cases that always reach it (above)


def wall(limit):
    return "the wall-time limit of a Lua call was reached: more than %s s of wall time in one call" % limit


WALL = wall("0.5")
ENDS = "beltsim ends here; the outputs written so far are kept"
BACKTRACKING = ['local x = ("a"):rep(3000):find("(.-)(.-)(.-)(.-)b")',
                'local x = ("a"):rep(3000):match("(.-)(.-)(.-)(.-)b")',
                'local x = ("a"):rep(3000):gsub("(.-)(.-)(.-)(.-)b", "")',
                'for x in ("a"):rep(3000):gmatch("(.-)(.-)(.-)(.-)b") do end']


class TimeLimits(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_time_")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def run_script(self, text, *flags, stdin=subprocess.DEVNULL):
        with open(os.path.join(self.dir, "s.lua"), "w") as f:
            f.write(text)
        p = subprocess.run([BELTSIM, "run", "s.lua", *flags], cwd=self.dir, stdin=stdin, capture_output=True,
                           text=True, timeout=BOUND)
        return p.returncode, p.stderr

    def test_patterns_that_backtrack_end_the_process(self):
        for form in BACKTRACKING:
            code, err = self.run_script("local y = 1\n" + form + "\n", "--max-lua-wall", SHORT)
            self.assertEqual(code, 1, form + ": " + err)
            self.assertIn("beltsim: s.lua: " + wall(SHORT), err, form)
            self.assertIn("--max-lua-wall S raises it, 0 removes it", err, form)
            self.assertIn(ENDS, err, form)

    def test_long_c_work_stops(self):
        # (form, stopped in the process for sure): a string.rep of 128 MB is one C call of about
        # 1.5 s here (a memcpy per character), which may outlast the 2 s of grace on a busy machine
        for form, inside in [("table.move({}, 1, 2^62, 2)", True),
                             ("local t = {} for i = 1, 1e5 do t[i] = {} end while true do collectgarbage() end", True),
                             ('while true do local s = ("x"):rep(2^27) end', False),
                             ('coroutine.wrap(function() while true do pcall(string.rep, "x", 2^27) end end)()', False),
                             ('local s = ("x"):rep(2^27) while true do local u = s:upper() end', False)]:
            for instructions in ["1e10", "0"]:
                code, err = self.run_script("local y = 1\n" + form + "\n", "--max-lua-wall", SHORT,
                                            "--max-instructions", instructions)
                self.assertEqual(code, 1, form + ": " + err)
                self.assertIn("beltsim: s.lua", err, form)
                self.assertIn(wall(SHORT), err, form)
                if inside:
                    self.assertNotIn(ENDS, err, form)

    def test_a_read_that_waits_ends_at_the_wall_time_limit(self):
        # stdin a pipe that nobody writes: io.read() waits, using no CPU time
        r, w = os.pipe()
        try:
            code, err = self.run_script("local y = 1\nlocal line = io.read()\n", "--max-lua-wall", "0.5",
                                        "--max-lua-cpu", "0.2", stdin=r)
        finally:
            os.close(r)
            os.close(w)
        self.assertEqual(code, 1, err)
        self.assertIn(WALL, err)
        self.assertIn(ENDS, err)

    def test_the_cpu_time_limit(self):
        code, err = self.run_script("local y = 1\nwhile true do end\n", "--max-lua-cpu", "0.3", "--max-lua-wall", "0")
        self.assertEqual(code, 1, err)
        self.assertIn("beltsim: s.lua:2: the CPU-time limit of a Lua call was reached: more than 0.3 s of CPU time", err)
        self.assertIn("--max-lua-cpu S raises it, 0 removes it", err)

    def test_bad_values_are_refused(self):
        for option in ["--max-lua-wall", "--max-lua-cpu"]:
            for value in ["-1", "nan", "1e10", "x"]:
                code, err = self.run_script("print(1)\n", option, value)
                self.assertEqual(code, 2, option + " " + value + ": " + err)
                self.assertIn(option, err)

    def test_a_sweep_point_that_hits_a_limit_fails_with_the_reason(self):
        with open(os.path.join(self.dir, "sw.lua"), "w") as f:
            f.write('return beltsim.sweep {\n'
                    '  grid = { k = {0, 1, 2} },\n'
                    '  run = function(p)\n'
                    '    if p.k == 1 then ' + BACKTRACKING[0] + ' end\n'
                    '    if p.k == 2 then while true do end end\n'
                    '    return { twice = 2 * p.k }\n'
                    '  end,\n'
                    '}\n')
        p = subprocess.run([BELTSIM, "sweep", "sw.lua", "--jobs", "1", "--max-lua-wall", "0.5"], cwd=self.dir,
                           capture_output=True, text=True, timeout=BOUND)
        self.assertEqual(p.returncode, 1, p.stderr)
        with open(os.path.join(self.dir, "out", "sw", "summary.csv"), newline="") as f:
            rows = list(csv.reader(f))
        status = {r[0]: r[rows[0].index("status")] for r in rows[1:]}
        self.assertEqual(status["0"], "ok")
        for k in ["1", "2"]:
            self.assertTrue(status[k].startswith("error: "), status[k])
            self.assertIn(WALL, status[k], k)
        self.assertIn(ENDS, status["1"])  # the process ended: its log's last line


if __name__ == "__main__":
    BELTSIM = sys.argv.pop(1)
    unittest.main(verbosity=2)
