#!/usr/bin/env python3
"""`beltsim plot` on the two kinds of CSV it draws (docs/cli.md#plot): a run's timeseries.csv,
against time, and a sweep's summary.csv, a column against another. An option the form of the
file would ignore is refused (exit 2) before anything is written: --from on a summary (its x is
a parameter, not time) once gave the PNG of every point, whatever T."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

BELTSIM = None

# a sweep's summary.csv as beltsim sweep writes it (sweep/results.hpp): point, the parameters,
# status, inputs, the figures
SUMMARY = """point,mu,pretension,status,inputs,slip
0,0.3,300,ok,x,0.5
1,0.3,500,ok,x,0.25
2,1,300,ok,x,0.125
3,1,500,ok,x,0.0625
"""

TIMESERIES = "t,driver.omega,driven.omega\n" + "".join(
    "%g,%g,%g\n" % (k * 0.01, k, 0.9 * k) for k in range(11))


def run(args, cwd):
    p = subprocess.run([BELTSIM] + args, capture_output=True, text=True, cwd=cwd, timeout=120)
    return p.returncode, p.stdout, p.stderr


class Forms(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_plot_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        for name, text in (("summary.csv", SUMMARY), ("timeseries.csv", TIMESERIES)):
            with open(os.path.join(self.dir, name), "w") as f:
                f.write(text)

    def exists(self, name):
        return os.path.exists(os.path.join(self.dir, name))

    def test_a_summary_is_drawn_against_its_first_column(self):
        code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--out", "all.png"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out, "all.png\n")
        self.assertTrue(self.exists("all.png"))

    def test_from_on_a_summary_is_refused_before_anything_is_written(self):
        # (it was ignored: --from 400 and --from 1e9 gave the bytes of the plot without it)
        for t in ("400", "1e9"):
            code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--from", t, "--out", "p.png"],
                                 self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn("beltsim: --from: summary.csv is a sweep's summary, drawn against its column pretension, "
                          "not against time, so --from (a start time) does not apply", err)
            self.assertIn("Run 'beltsim plot --help'", err)
            self.assertEqual(out, "")
            self.assertFalse(self.exists("p.png"))
        # with no columns named, the same refusal (not the summary's advice to name them)
        code, out, err = run(["plot", "summary.csv", "--from", "400"], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("drawn against the column named first", err)
        self.assertFalse(self.exists("plot.png"))

    def test_from_on_a_time_series_leaves_out_the_times_before(self):
        code, out, err = run(["plot", "timeseries.csv", "--from", "0.05", "--out", "late.png"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertTrue(self.exists("late.png"))
        code, out, err = run(["plot", "timeseries.csv", "--from", "1e9", "--out", "none.png"], self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("timeseries.csv has no samples at t >= 1e+09 s (its last is at 0.1 s)", err)
        self.assertFalse(self.exists("none.png"))

    def test_to_ends_the_window_as_summary_takes_it(self):
        # (a user's trial: plot took --from but refused --to, which summary takes)
        code, out, err = run(["plot", "timeseries.csv", "--out", "all.png"], self.dir)
        self.assertEqual(code, 0, err)
        code, out, err = run(["plot", "timeseries.csv", "--from", "0.02", "--to", "0.05", "--out", "mid.png"], self.dir)
        self.assertEqual(code, 0, err)
        with open(os.path.join(self.dir, "all.png"), "rb") as a, open(os.path.join(self.dir, "mid.png"), "rb") as b:
            self.assertNotEqual(a.read(), b.read())
        code, out, err = run(["plot", "timeseries.csv", "--from", "0.05", "--to", "0.02"], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("--from 0.05 lies after --to 0.02", err)
        code, out, err = run(["plot", "timeseries.csv", "--from", "0.021", "--to", "0.029", "--out", "gap.png"],
                             self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("timeseries.csv has no samples at 0.021 s <= t <= 0.029 s", err)
        code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--to", "400", "--out", "p.png"], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("--to (an end time) does not apply", err)
        self.assertFalse(self.exists("p.png"))

    def test_points_left_out_of_a_summary_are_named(self):
        # trial 27: 2 of 6 points failed, the figure drew 4 marks and nothing was said
        with open(os.path.join(self.dir, "failed.csv"), "w") as f:
            f.write("point,mu,pretension,status,inputs,slip\n"
                    "0,0.3,300,ok,x,0.5\n"
                    "1,0.3,-100,\"error: p.lua:9: belt.pretension must be > 0 (got -100 N)\",x,\n"
                    "2,1,300,not run,,\n"
                    "3,1,500,ok,x,0.0625\n")
        code, out, err = run(["plot", "failed.csv", "pretension", "slip", "--out", "f.png"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out, "f.png\n")
        self.assertEqual(err, "beltsim plot: warning: left out of the plot, with nothing to draw: 2 of the 4 points "
                              "(1 failed, 1 not run):\n"
                              "  point 1 (mu=0.3, pretension=-100): error: p.lua:9: belt.pretension must be > 0 "
                              "(got -100 N)\n"
                              "  point 2 (mu=1, pretension=300): not run\n")
        # every point drawn: no warning
        code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--out", "s.png"], self.dir)
        self.assertEqual((code, err), (0, ""))

    def test_by_draws_a_series_per_value_of_a_parameter(self):
        # trial 27 S1: the points of both mu shared one colour; --by mu draws a line per mu
        code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--out", "plain.png"], self.dir)
        self.assertEqual((code, err), (0, ""))
        code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--by", "mu", "--out", "by.png"], self.dir)
        self.assertEqual((code, out, err), (0, "by.png\n", ""))
        with open(os.path.join(self.dir, "plain.png"), "rb") as a, open(os.path.join(self.dir, "by.png"), "rb") as b:
            self.assertNotEqual(a.read(), b.read())
        code, out, err = run(["plot", "--help"], self.dir)
        self.assertIn("--by PARAM", out)

    def test_by_refuses_what_it_cannot_draw(self):
        # a column the summary has not: exit 1 (as any column it has not), with the close name
        code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--by", "Mu", "--out", "p.png"], self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("--by Mu: summary.csv has no column 'Mu' (did you mean 'mu'?); its columns: point, mu,", err)
        # the x or a y column: bad usage
        for by, axis in (("pretension", "x"), ("slip", "y")):
            code, out, err = run(["plot", "summary.csv", "pretension", "slip", "--by", by, "--out", "p.png"], self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn("--by %s: %s is drawn, as %s; --by takes another column" % (by, by, axis), err)
        # a time series: bad usage
        code, out, err = run(["plot", "timeseries.csv", "driver.omega", "--by", "mu", "--out", "p.png"], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("--by: timeseries.csv is a run's time series, drawn against t; --by (a series per value of a "
                      "column) is for a sweep's summary.csv", err)
        self.assertFalse(self.exists("p.png"))
        # a command that does not take it
        code, out, err = run(["summary", ".", "--by", "mu"], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("summary does not take: --by mu", err)

    def test_a_real_sweeps_summary(self):
        # tests/sweep/grid.lua (pretension x mu, 6 points of 0.02 s): the example of too few columns
        # names this summary's own (the x given, its first figure of numbers); --by mu draws a line
        # of slip against pretension per mu, every point drawn, nothing to warn of
        grid = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sweep", "grid.lua")
        code, out, err = run(["sweep", grid, "--jobs", "2", "--out", "grid"], self.dir)
        self.assertEqual(code, 0, err)
        code, out, err = run(["plot", "grid", "pretension"], self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("e.g. beltsim plot grid/summary.csv pretension omega.driven;", err)
        code, out, err = run(["plot", "grid", "pretension", "slip", "--by", "mu", "--out", "by.png"], self.dir)
        self.assertEqual((code, out, err), (0, "by.png\n", ""))
        self.assertGreater(os.path.getsize(os.path.join(self.dir, "by.png")), 5000)

    def test_options_plot_does_not_take(self):
        for option in ("--csv", "--rtol"):
            code, out, err = run(["plot", "summary.csv", "pretension", "slip", option, "1"], self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn("plot does not take: " + option, err)

    def test_a_runs_folder_is_drawn_from_its_timeseries(self):
        # trial 12: `plot DIR` said "cannot read DIR: it is a folder" where summary takes a run's folder;
        # a sweep's folder gives its summary.csv, a folder with neither names the file it lacks
        for name, text in (("run1", TIMESERIES), ("sweep1", SUMMARY)):
            os.mkdir(os.path.join(self.dir, name))
            with open(os.path.join(self.dir, name, "timeseries.csv" if name == "run1" else "summary.csv"), "w") as f:
                f.write(text)
        code, out, err = run(["plot", "run1", "driven.omega"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out, os.path.join("run1", "plot.png") + "\n")
        self.assertTrue(self.exists(os.path.join("run1", "plot.png")))
        code, out, err = run(["plot", "sweep1/", "pretension", "slip"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertTrue(self.exists(os.path.join("sweep1", "plot.png")))
        os.mkdir(os.path.join(self.dir, "empty"))
        code, out, err = run(["plot", "empty"], self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("cannot read empty/timeseries.csv: No such file or directory", err)

    def test_a_missing_file_is_exit_1_with_or_without_from(self):
        # (docs/cli.md: a file that cannot be read is exit 1; its kind cannot be known)
        for extra in ([], ["--from", "1"]):
            code, out, err = run(["plot", "missing.csv"] + extra, self.dir)
            self.assertEqual(code, 1, err)
            self.assertEqual(err, "beltsim: cannot read missing.csv: No such file or directory\n")


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
