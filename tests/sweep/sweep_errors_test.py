#!/usr/bin/env python3
"""`beltsim sweep`'s errors after the points are known, through the program: --collect refusing a
folder that holds no point of the sweep (and collecting its own whose points all died), a folder
that cannot be written, sbatch missing or printing megabytes, a point that cannot start, each said
in one line with nothing finished lost, Slurm scripts that quote every value, and a second sweep on
a folder in use refused, a --rerun stopped (or a point's process killed) keeping the results (and
their folders) that should stand, and the earlier folders a sweep killed outright left aside settled
by the next. The folder, the runs and the waits are sweep_test.py's.

usage: sweep_errors_test.py BELTSIM
"""
import os
import shutil
import signal
import subprocess
import sys
import time
import unittest

import sweep_test
from sweep_test import BAD, DRIVE, GRID, LIMIT, PLAIN, SweepCase, alive, rows

BELTSIM = None

# each point k of K (0, 1, ...) runs the drive for as long as the file T_END says (no run when
# T_END is ""), then waits until the file GATE exists (the script's folder is readable in the
# sandbox); point FAIL (none when -1), on line FAIL_LINE, then fails
GATED = """
local fail, t_end_file = %d, %r
return beltsim.sweep {
  grid = { k = {%s} },
  run = function(p)
    if t_end_file ~= "" then
      local f = assert(io.open(t_end_file))
      local t_end = tonumber(f:read("a"))
      f:close()
      beltsim.scene(require "drive" {}):run { t_end = t_end, sample = 1e-3, progress = false }
    end
    while true do
      local f = io.open(%r)
      if f then f:close() break end
    end
    if p.k == fail then error("asked to fail") end
    return { twice = 2 * p.k }
  end,
}
"""
FAIL_LINE = 16


class SweepErrors(SweepCase):
    def gated(self, points=2, fail=-1, t_end=""):
        """the GATED sweep in this test's folder and its gate (t_end: the file of its runs' length)"""
        script, gate = self.path("gated.lua"), self.path("go")
        with open(script, "w") as f:
            f.write(GATED % (fail, t_end, ", ".join(map(str, range(points))), gate))
        if t_end:
            shutil.copy(DRIVE, self.dir)
        return script, gate

    def processes_here(self):
        """the processes (not zombies) working in this test's folder: the sweep's and its points'"""
        found = []
        for pid in os.listdir("/proc"):
            try:
                if pid.isdigit() and os.readlink("/proc/%s/cwd" % pid) == self.dir and alive(int(pid)):
                    found.append(int(pid))
            except OSError:  # ended meanwhile, or not ours to read
                pass
        return found

    def assert_one_line_error(self, p, *words):
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertNotIn("terminate", p.stderr)
        # the error, said once, on the last line (after the notes of a point's run)
        last = p.stderr.splitlines()[-1]
        self.assertTrue(last.startswith("beltsim: "), p.stderr)
        self.assertEqual(p.stderr.count(last[len("beltsim: "):]), 1, p.stderr)
        for w in words:
            self.assertIn(w, last)

    def test_collect_refuses_a_folder_of_no_point_of_the_sweep(self):
        # --collect over another sweep's folder replaced its summary.csv with 'outdated' rows; over a
        # run's folder or a missing one it wrote a summary of 'not run' rows
        self.run_beltsim("sweep", GRID, "--point", "0", "--out", "grid")
        before = rows(self.path("grid", "0", "point.csv"))
        shutil.copy(DRIVE, self.dir)
        shutil.copy(GRID, self.path("other.lua"))  # another sweep file of the same points
        p = self.run_beltsim("sweep", "other.lua", "--collect", "--out", "grid", ok=(1,))
        self.assert_one_line_error(p, "--collect: grid holds the points of %s, not of other.lua" % GRID)
        p = self.run_beltsim("sweep", BAD, "--collect", "--out", "grid", ok=(1,))  # points of other parameters
        self.assert_one_line_error(p, "--collect: no point of %s has run in grid" % BAD)
        self.assertFalse(os.path.exists(self.path("grid", "summary.csv")))
        self.assertEqual(rows(self.path("grid", "0", "point.csv")), before)
        os.makedirs(self.path("run"))
        p = self.run_beltsim("sweep", GRID, "--collect", "--out", "run", ok=(1,))
        self.assert_one_line_error(p, "--collect: no point of %s has run in run" % GRID, "nothing to collect")
        self.assertEqual(os.listdir(self.path("run")), [])
        p = self.run_beltsim("sweep", GRID, "--collect", "--out", "none", ok=(1,))
        self.assert_one_line_error(p, "--collect: none is not a folder: nothing to collect")
        self.assertFalse(os.path.exists(self.path("none")))
        # the sweep's own folder whose points all died before a result (a Slurm array cancelled): its
        # job scripts or a point's folder are there, and every point is 'not run'
        for what in ("sweep.sbatch", "3"):
            os.makedirs(self.path("died"), exist_ok=True)
            if what == "3":
                os.makedirs(self.path("died", "3"))
            else:
                with open(self.path("died", what), "w") as f:
                    f.write("srun beltsim sweep '%s' --out ... --point $SLURM_ARRAY_TASK_ID\n" % GRID)
            p = self.run_beltsim("sweep", GRID, "--collect", "--out", "died", ok=(1,))
            self.assertIn("0 ok, 0 failed, 6 not run", p.stderr)
            shutil.rmtree(self.path("died"))
        # the sweep's own folder, one point run: merged, the others not run
        p = self.run_beltsim("sweep", GRID, "--collect", "--out", "grid", ok=(1,))
        self.assertIn("1 ok, 0 failed, 5 not run", p.stderr)

    def test_a_run_into_a_study_is_refused(self):
        # `beltsim run S.lua` after `beltsim sweep S.lua --set ...` wrote its outputs into out/S,
        # the study's folder, among its summary.csv and points
        def tree(top):
            found = {}
            for folder, _, files in os.walk(self.path(top)):
                for name in files:
                    with open(os.path.join(folder, name), "rb") as f:
                        found[os.path.relpath(os.path.join(folder, name), self.dir)] = f.read()
            return found

        self.run_beltsim("sweep", PLAIN, "--set", "pretension=300,500")
        self.run_beltsim("sweep", GRID, "--point", "1")  # a study of one point, without summary.csv yet
        before = tree("out")
        shutil.copy(DRIVE, self.dir)  # (--trusted: require from the folder beltsim runs in)
        for script, args, folder, names in ((PLAIN, [], "out/plain", "pretension"),
                                            (PLAIN, ["--out", "out/plain"], "out/plain", "pretension"),
                                            (PLAIN, ["--out", "out/grid/", "--trusted"], "out/grid/", "mu, pretension")):
            p = self.run_beltsim("run", script, *args, ok=(1,))
            self.assertIn("beltsim: %s:4: run.out: the output folder %s holds a study of `beltsim sweep` (its "
                          "summary.csv and a folder per point; its points vary %s), among whose files this run's "
                          "outputs would lie: give the run a folder of its own (--out DIR, or out = ... in the "
                          "script), or remove %s first\n" % (script, folder, names, folder), p.stderr)
            self.assertEqual(tree("out"), before)
        # elsewhere it runs; so do wp (its runs go to out/plain/wp) and a point of the study
        self.run_beltsim("run", PLAIN, "--out", "out/plain_run")
        self.run_beltsim("wp", PLAIN, "--integrators", "esdirk32", "--rtols", "1e-2", "--ref-rtol", "1e-3")
        self.assertTrue(os.path.exists(self.path("out", "plain", "wp", "wp.csv")))
        self.run_beltsim("sweep", PLAIN, "--set", "pretension=300,500", "--point", "1")

    def test_sbatch_missing_is_an_error_not_an_abort(self):
        empty = self.path("bin")
        os.mkdir(empty)
        p = subprocess.run([BELTSIM, "sweep", GRID, "--slurm", "--submit"], cwd=self.dir, capture_output=True,
                           text=True, timeout=300, env=dict(os.environ, PATH=empty))
        self.assert_one_line_error(p, "sbatch", "PATH")
        self.assertTrue(os.path.exists(self.path("out", "grid", "sweep.sbatch")))

    def test_slurm_scripts_quote_every_value_or_refuse_it(self):
        # a folder whose name the shell (a space, ', #, $) and Slurm's --output pattern (%x, the
        # job's name) would both read otherwise: quoted for each, and for the submit hint
        folder = self.path("mu%x 'q' #1 $HOME")
        p = self.run_beltsim("sweep", GRID, "--slurm", "--out", folder)
        with open(os.path.join(folder, "sweep.sbatch")) as f:
            self.assertIn('\n#SBATCH --output="%s/slurm-%%A_%%a.out"\n' % folder.replace("%", "%%"), f.read())
        for name in ("sweep.sbatch", "collect.sbatch"):
            check = subprocess.run(["sh", "-n", os.path.join(folder, name)], capture_output=True, text=True)
            self.assertEqual(check.returncode, 0, check.stderr)
        quoted = "'%s/sweep.sbatch'" % folder.replace("'", "'\\''")
        self.assertIn("jid=$(sbatch --parsable %s)" % quoted, p.stderr)
        # a line break in --out, in the sweep file's path or its name would end a line of the
        # script and run the rest as a command: refused, nothing made
        odd = self.path("x\ntouch pwned")
        os.mkdir(odd)
        shutil.copy(GRID, os.path.join(odd, "grid.lua"))
        shutil.copy(GRID, self.path("g\nrid.lua"))
        for args in ([GRID, "--out", "a\nb"], [GRID, "--out", "a\r\nb"], [GRID, "--out", "x\n#SBATCH --wrap=touch pwned"],
                     [os.path.join(odd, "grid.lua"), "--out", "odd"], [self.path("g\nrid.lua"), "--out", "odd"]):
            p = self.run_beltsim("sweep", *args, "--slurm", ok=(2,))
            self.assertIn("control character", p.stderr)
            self.assertNotIn("\ntouch", p.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), sorted(["g\nrid.lua", "mu%x 'q' #1 $HOME", "x\ntouch pwned"]))
        # times and partitions Slurm would not take, or would take as no limit
        for args in (["--time", "-1"], ["--time=0"], ["--time", "1-2-3"], ["--partition=-x"], ["--partition", "a,,b"]):
            p = self.run_beltsim("sweep", GRID, "--slurm", "--out", "t", *args, ok=(2,))
            self.assertIn(args[0].split("=")[0] + ":", p.stderr)
        self.assertFalse(os.path.exists(self.path("t")))

    def test_an_sbatch_that_prints_megabytes_is_an_error_of_one_short_line(self):
        # 50 MB of digits on one line was taken whole as a job id
        fake = self.path("bin")
        os.mkdir(fake)
        with open(os.path.join(fake, "sbatch"), "w") as f:
            f.write("#!/bin/sh\nhead -c 50000000 /dev/zero | tr '\\0' 7\n")
        os.chmod(os.path.join(fake, "sbatch"), 0o755)
        p = subprocess.run([BELTSIM, "sweep", GRID, "--slurm", "--submit"], cwd=self.dir, capture_output=True,
                           text=True, timeout=300, env=dict(os.environ, PATH=fake + ":" + os.environ["PATH"]))
        self.assert_one_line_error(p, "sbatch", "printed more than 65536 bytes")
        self.assertLess(len(p.stderr), 2000)
        self.assertEqual(p.stdout.count("\n"), 2, p.stdout)  # the scripts' paths, no job ids

    def test_a_folder_that_cannot_be_written_is_an_error_not_an_abort(self):
        with open(self.path("blocker"), "w") as f:
            f.write("a file, not a folder\n")
        for mode in ([], ["--collect"], ["--slurm"]):
            p = self.run_beltsim("sweep", GRID, "--out", "blocker/sweep", *mode, ok=(0, 1, 2, 134, -6))
            self.assert_one_line_error(p, "blocker/sweep")
        # a point's result that cannot be written (its name taken by a folder)
        os.makedirs(self.path("out", "grid", "4", "point.csv"))
        p = self.run_beltsim("sweep", GRID, "--point", "4", ok=(0, 1, 2, 134, -6))
        self.assert_one_line_error(p, "point.csv")

    def test_a_point_that_cannot_start_stops_the_sweep_and_keeps_what_finished(self):
        # point 1's log.txt is a folder: point 0 finishes first (one job), then the sweep stops
        os.makedirs(self.path("out", "plain", "1", "log.txt"))
        args = ["sweep", PLAIN, "--set", "pretension=300,500,700"]
        p = self.run_beltsim(*args, "--jobs", "1", ok=(0, 1, 134, -6))
        self.assert_one_line_error(p, "out/plain/1/log.txt")
        summary = rows(self.path("out", "plain", "summary.csv"))
        self.assertEqual([r[2] for r in summary[1:]], ["ok", "not run", "not run"])
        # two jobs: point 0 runs (and waits) when point 1 cannot start; it is stopped and reaped
        # before the sweep ends, and the folder is left as a stop leaves it
        script, gate = self.gated()
        os.makedirs(self.path("out", "gated", "1", "log.txt"))
        p = self.run_beltsim("sweep", script, "--jobs", "2", ok=(0, 1, 134, -6))
        self.assert_one_line_error(p, "out/gated/1/log.txt")
        self.assertEqual(self.processes_here(), [], "a point's process outlived the sweep")
        summary = rows(self.path("out", "gated", "summary.csv"))
        self.assertEqual([r[2] for r in summary[1:]], ["not run", "not run"])
        # the cause gone, the sweep runs to its end
        os.rmdir(self.path("out", "gated", "1", "log.txt"))
        with open(gate, "w"):
            pass
        self.run_beltsim("sweep", script, "--jobs", "2")
        self.assertEqual([r[2] for r in rows(self.path("out", "gated", "summary.csv"))[1:]], ["ok", "ok"])

    def test_a_second_sweep_on_a_folder_in_use_is_refused(self):
        script, gate = self.gated()
        first = subprocess.Popen([BELTSIM, "sweep", script, "--jobs", "1"], cwd=self.dir, stderr=subprocess.PIPE,
                                 text=True)
        self.addCleanup(first.kill)
        self.wait_for(self.path("out", "gated", "0", "log.txt"), first)
        for mode in (["--jobs", "1"], ["--collect"], ["--slurm"]):
            p = self.run_beltsim("sweep", script, *mode, ok=(0, 1, 2))
            self.assert_one_line_error(p, "out/gated", "another sweep is running there")
        self.assertIsNone(first.poll(), "the first sweep ended while the second was refused")
        with open(gate, "w"):
            pass
        _, err = first.communicate(timeout=LIMIT)
        self.assertEqual(first.returncode, 0, err)
        self.assertEqual([r[2] for r in rows(self.path("out", "gated", "summary.csv"))[1:]], ["ok", "ok"])
        self.assertFalse(os.path.exists(self.path("out", "gated", "sweep.sbatch")), "the refused --slurm wrote")

    def kept_folders(self):
        """the earlier folders of the points running again (or left by a sweep killed outright)"""
        return sorted(n for n in os.listdir(self.path("out", "gated")) if n.startswith(".kept-"))

    def wait_until(self, what, proc, test):
        end = time.monotonic() + LIMIT
        while not test():
            self.assertIsNone(proc.poll(), "the sweep ended before " + what)
            self.assertLess(time.monotonic(), end, "never " + what)
            time.sleep(0.005)

    def test_a_stopped_rerun_keeps_the_earlier_results(self):
        # four points, point 3 failing, run to their end, each with a run of 0.02 s; then --rerun
        # with runs of 0.01 s, gated: point 0's process is killed (its run ended: its result
        # replaced), point 2 starts in its place, and the sweep is stopped while 1 and 2 wait. The
        # points whose run did not end keep their earlier results and folders, byte for byte (they
        # were 'not run'), and the last progress line counts what the closing line does
        t_end = self.path("t_end")
        with open(t_end, "w") as f:
            f.write("0.02")
        script, gate = self.gated(points=4, fail=3, t_end=t_end)
        with open(gate, "w"):
            pass
        self.run_beltsim("sweep", script, "--jobs", "2", ok=(1,))
        before = rows(self.path("out", "gated", "summary.csv"))
        self.assertEqual([r[2] for r in before[1:]],
                         ["ok", "ok", "ok", "error: %s:%d: asked to fail" % (script, FAIL_LINE)])
        files = ("point.csv", "log.txt", "timeseries.csv", "parameters.csv")
        earlier = {k: {n: self.read("out", "gated", str(k), n) for n in files} for k in range(4)}
        with open(t_end, "w") as f:
            f.write("0.01")
        os.remove(gate)
        proc = subprocess.Popen([BELTSIM, "sweep", script, "--jobs", "2", "--rerun"], cwd=self.dir,
                                stderr=subprocess.PIPE, text=True)
        self.addCleanup(proc.kill)
        self.point_process(proc, 1)
        # point 1 runs in a folder of its own, its earlier one aside
        self.wait_until("point 1's run wrote", proc, lambda: os.path.exists(self.path("out", "gated", "1",
                                                                                      "timeseries.csv")))
        self.assertIn(".kept-1", self.kept_folders())
        os.kill(self.point_process(proc, 0), signal.SIGKILL)
        self.point_process(proc, 2)
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=LIMIT)
        self.assertEqual(proc.returncode, 143, err)
        after = rows(self.path("out", "gated", "summary.csv"))
        self.assertRegex(after[1][2], r"^error: its process was killed by signal 9 \(out/gated/0/log.txt")
        self.assertEqual(after[2:], before[2:])
        for k in (1, 2, 3):
            self.assertEqual({n: self.read("out", "gated", str(k), n) for n in files}, earlier[k], k)
        # point 0's run ended (its process died): its folder is that run's, saying why
        self.assertNotEqual(self.read("out", "gated", "0", "log.txt"), earlier[0]["log.txt"])
        self.assertEqual(self.kept_folders(), [])
        self.assertIn("sweep gated: stopped before 3 points ran again: they keep their earlier results (2 ok, 1 failed)\n",
                      err)
        self.assertEqual(self.assert_counts_agree(err), (2, 2, 0))

        # --rerun again, the sweep killed outright while points 0 and 1 run: their earlier folders
        # are left aside, their folders partial; and point 2's earlier folder is left beside the
        # result of its run (as when the sweep is killed between the two)
        proc = subprocess.Popen([BELTSIM, "sweep", script, "--jobs", "2", "--rerun"], cwd=self.dir,
                                stderr=subprocess.DEVNULL)
        self.addCleanup(proc.kill)
        children = [self.point_process(proc, k) for k in (0, 1)]
        self.wait_until("point 1's run wrote", proc, lambda: os.path.exists(self.path("out", "gated", "1",
                                                                                      "timeseries.csv")))
        proc.kill()
        proc.wait(timeout=LIMIT)
        for c in children:
            end = time.monotonic() + LIMIT
            while alive(c):
                self.assertLess(time.monotonic(), end, "point process %d outlived the sweep" % c)
                time.sleep(0.005)
        self.assertEqual(self.kept_folders(), [".kept-0", ".kept-1"])
        self.assertNotIn("point.csv", os.listdir(self.path("out", "gated", "1")))
        shutil.copytree(self.path("out", "gated", "2"), self.path("out", "gated", ".kept-2"))
        os.remove(self.path("out", "gated", ".kept-2", "timeseries.csv"))  # (told from the result's)
        # a run of the sweep after it says what it did with each, and the failed points alone run again
        with open(gate, "w"):
            pass
        p = self.run_beltsim("sweep", script, "--jobs", "2", ok=(1,))
        for k in (0, 1):
            self.assertIn("sweep gated: point %d was running again when a sweep ended (killed outright?): its earlier "
                          "folder put back from out/gated/.kept-%d to out/gated/%d (the partial one removed), with its "
                          "earlier result\n" % (k, k, k), p.stderr)
        self.assertIn("sweep gated: point 2 had run again to a result when a sweep ended (killed outright?) before "
                      "removing its earlier folder: out/gated/.kept-2 removed\n", p.stderr)
        self.assertIn("2 of 4 points done already", p.stderr)
        self.assertEqual(self.kept_folders(), [])
        self.assertEqual([r[2] for r in rows(self.path("out", "gated", "summary.csv"))[1:]], [r[2] for r in before[1:]])
        for k in (1, 2):
            self.assertEqual({n: self.read("out", "gated", str(k), n) for n in files}, earlier[k], k)

if __name__ == "__main__":
    BELTSIM = sweep_test.BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
