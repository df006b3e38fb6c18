#!/usr/bin/env python3
"""`beltsim modes` and `sim:modes{}` (docs/modes.md) as a user meets them: the table, modes.csv, the
mode shapes' pictures, a Campbell diagram's CSV and picture, and bad options. The physics is
checked in tests/physics/modes_test.cpp; here, that what the command writes says the same: the
paper's two free pulleys turning against each other at rest lie where that test's lumped model puts
them (between 139.8 and 144.6 Hz with a flexible belt, 60 elements; the default belt with its
bending dampers on 40 elements, whose spans' springs reach further onto the wraps, measured 127.7 Hz:
the bound 125-150 Hz only says that the command reads the mode it means)."""
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None


def run(args, cwd=None):
    p = subprocess.run([BELTSIM] + args, capture_output=True, text=True, cwd=cwd, timeout=300)
    return p.returncode, p.stdout, p.stderr


class Modes(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_modes_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.script = os.path.join(self.dir, "s.lua")
        with open(self.script, "w") as f:
            f.write(two_pulley(elements=40, inertia=0.025) + "drive:run { t_end = 0.05, progress = false }\n")

    def test_modes_at_rest(self):
        out_dir = os.path.join(self.dir, "m")
        code, out, err = run(["modes", self.script, "--at", "0", "--out", out_dir, "--shapes", "2"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("mode     f [Hz]     zeta  where the kinetic energy is", out)
        with open(os.path.join(out_dir, "modes.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(list(rows[0].keys())[:4], ["mode", "frequency_Hz", "damping_ratio", "decay_1_s"])
        for g in ["span_driver_driven", "span_driven_driver", "wrap_driver", "pulley_driver", "pulley_driven"]:
            self.assertIn(g, rows[0])
        # shares sum to 1 in every mode
        for r in rows:
            self.assertAlmostEqual(sum(float(v) for k, v in r.items() if k not in
                                       ("mode", "frequency_Hz", "damping_ratio", "decay_1_s")), 1.0, places=9)
        torsion = [r for r in rows if float(r["pulley_driver"]) + float(r["pulley_driven"]) > 0.8]
        self.assertTrue(torsion, out)
        self.assertTrue(125 < float(torsion[0]["frequency_Hz"]) < 150, torsion[0])
        shapes = sorted(os.listdir(os.path.join(out_dir, "shapes")))
        self.assertEqual(len(shapes), 2)
        self.assertTrue(shapes[0].startswith("mode_01_") and shapes[0].endswith("Hz.png"), shapes)

    def test_a_mode_growing_at_rest_is_warned_of(self):
        # a user's trial: three pulleys (one on a tensioner arm) on a 6PK belt of 300 elements, at
        # rest, gravity 0: modes listed mode 2 at 84 Hz with zeta -0.56, which its check in time
        # finds at 131 Hz, zeta 0.05. A state at rest holds no energy for a mode to grow from; the
        # warning names the mode and --check. The test scene with no growing mode has no warning
        # (test_modes_at_rest's; asserted below), so the warning does not fire on every analysis
        scene = os.path.join(self.dir, "rest300.lua")
        with open(scene, "w") as f:
            f.write("""drive = beltsim.scene {
  pulleys = {
    { name = "crank", centre = {0, 0}, radius = 0.05, inertia = 0.01, torque = 0 },
    { name = "idler", centre = {0.15, 0.2}, radius = 0.05, inertia = 5e-5,
      tensioner = { pivot = {0.21, 0.2}, inertia = 1e-3, stiffness = 30, damping = 0.05 } },
    { name = "alt", centre = {0.3, 0}, radius = 0.05, inertia = 2e-3, torque = 0 },
  },
  gravity = 0,
  belt = { preset = "6PK", elements = 300, pretension = 300, direction = "cw" },
}
drive:run { t_end = 0.05, progress = false }
""")
        code, out, err = run(["modes", scene, "--at", "0", "--fmax", "130", "--out", os.path.join(self.dir, "g")],
                             cwd=self.dir)
        self.assertEqual(code, 0, err)
        growing = [ln.split() for ln in out.splitlines() if re.match(r"\s+\d+\s+[0-9.]+\s+-[0-9.]+\s", ln)]
        self.assertTrue(growing, out)  # the eigensolver's growing mode this test is about
        numbers = ", ".join(g[0] for g in growing)
        self.assertIn("warning: mode%s %s grow" % ("s" if len(growing) > 1 else "", numbers), err)
        self.assertIn("--check %s integrates" % numbers, err)
        code, out, err = run(["modes", self.script, "--at", "0", "--out", os.path.join(self.dir, "h")], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertNotIn(" grow", err)

    def test_an_earlier_analysis_pictures_are_removed(self):
        # the shapes of an earlier analysis (another time, more modes, a video) were left beside this
        # one's: the folder mixed mode_01_122.6Hz.png and mode_01_26.8Hz.png (docs/outputs.md, a
        # folder holds one run's outputs); files of other names stay
        shapes = os.path.join(self.dir, "m", "shapes")
        os.makedirs(shapes)
        stale = ["mode_01_26.8Hz.png", "mode_03_134.0Hz.png", "mode_01_26.8Hz.mp4", "mode_12_1287.0Hz.png"]
        kept = ["mode_01_26.8Hz.png.keep", "my_mode_01_26.8Hz.png", "notes.txt"]
        for f in stale + kept:
            with open(os.path.join(shapes, f), "w") as g:
                g.write("x")
        args = ["modes", self.script, "--at", "0", "--out", os.path.join(self.dir, "m")]
        code, out, err = run(args + ["--shapes", "2"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        drawn = [os.path.basename(ln) for ln in out.splitlines() if "/shapes/" in ln]
        self.assertEqual(len(drawn), 2, out)
        self.assertEqual(sorted(os.listdir(shapes)), sorted(drawn + kept))
        code, out, err = run(args + ["--shapes", "0"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(sorted(os.listdir(shapes)), sorted(kept))

    def test_check_in_time(self):
        # the pulleys' torsional mode at rest, pushed and run on, moves as the linearization says;
        # a mode number past the list is refused under the table, before modes.csv and the shapes are
        # written (they were written first, then refused)
        out_dir = os.path.join(self.dir, "k")
        code, out, err = run(["modes", self.script, "--at", "0", "--out", out_dir, "--shapes", "0"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        with open(os.path.join(out_dir, "modes.csv")) as f:
            rows = list(csv.DictReader(f))
        torsion = [r for r in rows if float(r["pulley_driver"]) + float(r["pulley_driven"]) > 0.8][0]["mode"]
        code, out, err = run(["modes", self.script, "--at", "0", "--out", out_dir, "--shapes", "0",
                              "--check", torsion], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertRegex(out, r"check of mode %s \([0-9.]+ Hz, zeta [0-9.]+\): pushed and run on, watched at "
                              r"[a-z_]+ (angle|middle): [0-9.]+ Hz, zeta [0-9.]+; .*: agrees\n" % torsion)
        past = os.path.join(self.dir, "past")
        code, out, err = run(["modes", self.script, "--at", "0", "--out", past, "--shapes", "1",
                              "--check", "%s,%d" % (torsion, len(rows) + 1)], cwd=self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("--check: there is no mode %d (%d listed)" % (len(rows) + 1, len(rows)), err)
        self.assertIn("%5d " % len(rows), out)  # the table, to choose from
        self.assertNotIn("check of mode", out)
        self.assertFalse(os.path.exists(os.path.join(past, "modes.csv")))
        self.assertFalse(os.path.exists(os.path.join(past, "shapes")))

    def test_campbell(self):
        out_dir = os.path.join(self.dir, "c")
        code, out, err = run(["modes", self.script, "--out", out_dir, "--campbell", "driver", "--rpm", "200:400:2",
                              "--settle", "0.06", "--orders", "2,4"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        with open(os.path.join(out_dir, "campbell.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(sorted({r["rpm"] for r in rows}), ["200", "400"])
        self.assertTrue(os.path.getsize(os.path.join(out_dir, "campbell.png")) > 1000)
        self.assertTrue(os.path.isfile(os.path.join(out_dir, "rpm_400", "timeseries.csv")))

    def test_modes_locked_at_half_the_passing_rate_are_named(self):
        # the paper's dry drive at 0.5 s on 60 elements: the passing (340.5 a second) locks modes of
        # its slack span at ν/2 = 170.27 Hz (docs/modes.md); the note under the table names exactly
        # those of modes.csv at ν/2
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "paper_dry.lua")
        out_dir = os.path.join(self.dir, "h")
        code, out, err = run(["modes", script, "--at", "0.5", "--shapes", "0", "--fmax", "200", "--out", out_dir],
                             cwd=self.dir)
        self.assertEqual(code, 0, err)
        passing = [ln for ln in out.splitlines() if "elements a second" in ln]
        self.assertEqual(len(passing), 1, out)
        nu = float(passing[0].split("ms, ")[1].split(" elements")[0])
        with open(os.path.join(out_dir, "modes.csv")) as f:
            freq = {r["mode"]: float(r["frequency_Hz"]) for r in csv.DictReader(f)}
        # the locked modes share one frequency to the last digit, the one nearest ν/2 (ν as printed,
        # to 4 digits); a free mode near it has a frequency of its own
        lock = min(freq.values(), key=lambda f: abs(f - nu / 2))
        self.assertLess(abs(lock - nu / 2), 1e-3 * nu, out)
        half = [m for m, f in freq.items() if abs(f - lock) <= 1e-9 * lock]
        self.assertGreaterEqual(len(half), 2, out)  # a pair split on the negative axis at least
        note = [ln for ln in out.splitlines() if "at half the passing rate" in ln]
        self.assertEqual(len(note), 1, out)
        self.assertTrue(note[0].startswith("modes " + ", ".join(half) + " at half the passing rate"), note[0])

    def test_bad_options(self):
        for args, message in [(["--campbell", "crank", "--rpm", "1:2:3"], "--campbell: the scene has no pulley 'crank'"),
                              (["--campbell", "drivr", "--rpm", "1:2:3"],
                               "--campbell: the scene has no pulley 'drivr' (did you mean 'driver'?); its pulleys: "
                               "driver, driven"),
                              (["--campbell", "driver"], "--campbell needs --rpm FROM:TO:COUNT"),
                              (["--campbell", "driver", "--rpm", "1:2"], "--rpm takes FROM:TO:COUNT"),
                              (["--fmin", "10", "--fmax", "5"], "--fmin must be >= 0 and below --fmax"),
                              (["--at", "-1"], "--at must be a time >= 0"),
                              (["--check", "0"], "--check must be a whole number >= 1, got 0"),
                              (["--campbell", "driver", "--rpm", "0:100:2"], "--rpm takes speeds > 0 rpm, got "
                                                                             "'0:100:2'"),
                              (["--campbell", "driver", "--rpm", "100", "--settle", "-1"],
                               "--settle must be a time > 0 [s], got '-1'"),
                              (["--campbell", "driver", "--rpm", "100", "--orders", "2,"], "--orders takes positive "
                                                                                         "engine orders"),
                              (["--check", ""], "--check takes mode numbers separated by commas"),
                              (["--check", "1", "--campbell", "driver", "--rpm", "1:2:2"],
                               "--check goes with the modes of one operating point (--at), not with --campbell: a "
                               "Campbell diagram checks no mode in time")]:
            code, out, err = run(["modes", self.script, "--out", os.path.join(self.dir, "x")] + args, cwd=self.dir)
            self.assertEqual(code, 2, err)
            self.assertIn(message, err)

    def test_an_option_of_the_other_form_is_refused_before_the_script_runs(self):
        # --rpm, --orders and --settle without --campbell gave an ordinary table, and --at, --shapes
        # and --video with it were dropped (exit 0): each given is named, exit 2, the script not run
        script = os.path.join(self.dir, "p.lua")
        with open(script, "w") as f:
            f.write('print("the script ran")\n' + two_pulley(elements=40, inertia=0.025) +
                    "drive:run { t_end = 0.05, progress = false }\n")
        for args, message in [
                (["--rpm", "600:3000:3", "--orders", "2", "--settle", "0.1", "--at", "0"],
                 "--rpm, --orders and --settle go with --campbell PULLEY (a Campbell diagram): the modes of one "
                 "operating point (--at) do not use them"),
                (["--settle", "0.1"], "--settle goes with --campbell PULLEY (a Campbell diagram): the modes of one "
                                      "operating point (--at) do not use it"),
                (["--campbell", "driver", "--rpm", "600:1200:2", "--at", "0.05", "--shapes", "3", "--video"],
                 "--at, --shapes and --video go with the modes of one operating point (--at), not with --campbell: "
                 "a Campbell diagram takes each speed's modes after --settle and draws no mode shapes"),
                (["--campbell", "driver", "--rpm", "600", "--video", "--check", "1"],
                 "--video and --check go with the modes of one operating point (--at), not with --campbell: a "
                 "Campbell diagram draws no mode shapes and checks no mode in time"),
                (["--shapes", "0", "--video"], "--video makes a video of each mode drawn, and --shapes 0 draws none")]:
            out_dir = os.path.join(self.dir, "o")
            code, out, err = run(["modes", script, "--out", out_dir] + args, cwd=self.dir)
            self.assertEqual(code, 2, args)
            self.assertIn("beltsim: " + message + "\n", err)
            self.assertNotIn("the script ran", out)
            self.assertFalse(os.path.exists(out_dir), args)

    def test_lua_call(self):
        path = os.path.join(self.dir, "l.lua")
        with open(path, "w") as f:
            f.write(two_pulley(elements=40, inertia=0.025) +
                    'local sim = drive:start { out = "o", progress = false }\n'
                    'local m = sim:modes { fmax = 500, csv = "modes.csv", shapes = 1 }\n'
                    'for k, mode in ipairs(m) do print(k, mode.frequency, mode.damping, mode.where) end\n'
                    'print(m.csv, #m.pictures, m.groups[1])\n'
                    # at rest the state's own modes (no passing); at speed (0.15 s: 3.4 m/s) the
                    # Floquet modes of one element passing, the driver's torque still ramping: the
                    # drive is forced and speeds up by more than 1 % over the passing (measured
                    # 12 %; sim/modes.hpp, sim/floquet.hpp)
                    'print("at rest", m.period, m.forced)\n'
                    'sim:run_to(0.15)\nlocal r = sim:modes { fmax = 500 }\n'
                    'print("at speed", r.period > 0, r.velocity_defect > 0.01, r.forced, r.velocity_defect)\n'
                    'sim:modes { shapes = 1.5 }\n')
        code, out, err = run(["run", path], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("o/modes.csv\t1\tspan_driver_driven", out)
        self.assertIn("at rest\t0.0\tnil", out)
        self.assertIn("at speed\ttrue\ttrue\tdriver\t", out)
        self.assertIn("l.lua:17: sim:modes: shapes must be a whole number of modes to draw, 0 to 1000 (got 1.5)", err)
        self.assertTrue(os.path.isfile(os.path.join(self.dir, "o", "modes.csv")))


if __name__ == "__main__":
    BELTSIM = sys.argv.pop(1)
    unittest.main(verbosity=2)
