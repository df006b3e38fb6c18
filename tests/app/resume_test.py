#!/usr/bin/env python3
"""beltsim.resume and sim:save through the program, as a user's trial met them:
- a checkpoint resumed (rewind = true) after the same script ran again into its folder with another
  pretension is refused, naming the files that differ, and nothing is changed (it kept the later
  run's rows up to the checkpoint and the checkpoint's run's after them, exit 0); the rerun warned
  of nothing, and now names the checkpoint it leaves behind;
- a checkpoint whose run's folder was moved away is refused without making an empty folder there;
- a simulation with a Lua function law is said not to be savable where it is saved: sim:save names
  the pulley and the law; a script that never saves hears nothing of it (scene:start warned at
  every start, saved or not)."""
import csv
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

BELTSIM = None


def scene(pretension):
    """the trial's two-pulley drive (60 elements, the driver's torque ramped to -40 N·m over 0.1 s,
    the driven pulley's proportional to its speed) as `drive`, its belt's pretension the Lua
    expression given"""
    return """
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0, 0}, radius = 0.1, torque = beltsim.ramp(0.1, -40) },
    { name = "driven", centre = {0.29, 0}, radius = 0.1, torque = { per_speed = -0.955 } },
  },
  belt = { elements = 60, pretension = %s },
}
""" % pretension


# the trial's drive: --set save=true saves out/drive/mid.ckpt at 0.1 s and runs on to 0.2 s;
# --set pretension=P changes the belt
DRIVE = """
local save, t_end = beltsim.args.save, beltsim.args.t_end or 0.2
""" + scene("beltsim.args.pretension or 500") + """
local sim = drive:start { out = beltsim.args.out or "out/drive", progress = false }
sim:run_to(0.1)
if save then sim:save("mid.ckpt") end
sim:run_to(t_end)
sim:close()
"""

RESUME = """
local sim = beltsim.resume(beltsim.args.ck, { rewind = true, progress = false })
sim:run_to(0.2)
sim:close()
"""

# a step of the driven pulley's torque at 0.01 s and a wetting of the whole belt at 0.02 s, both at
# sample and frame times (frames every 1/300 s: 3/300 and 6/300), a state kept at each frame
EVENTS = """
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0, 0}, radius = 0.1, torque = beltsim.ramp(0.02, -40) },
    { name = "driven", centre = {0.29, 0}, radius = 0.1, torque = beltsim.step(0.01, 0, 3) },
  },
  belt = { elements = 40, pretension = 500, direction = "cw" },
}
drive:run { t_end = 0.03, sample = 1e-3, progress = false, out = "out/events", keep_states = true,
  frames = { fps = 30, slowdown = 10, png = false, video = false },
  events = { { t = 0.02, mu = 0.2 } } }
"""

# the resumed simulation slowed by a callback that waits on the CPU clock (50 ms of it each
# simulated ms: the 0.1 s to run take 5 s at least), with beltsim.resume's max_wall from --set
SLOW_RESUME = """
local function wait(s) local c = os.clock() while os.clock() - c < s do end end
local sim = beltsim.resume(beltsim.args.ck, { rewind = true, progress = false, max_wall = beltsim.args.max_wall })
sim:every(0.001, function() wait(0.05) end)
sim:run_to(0.2)
sim:close()
"""

# trial 22's what-if: the drive saved at 0.05 s and wetted (mu 0.2) to 0.1 s; the checkpoint
# resumed into a folder of its own (out) while the first simulation still runs, wetted otherwise
# (mu 0.05) to 0.1 s; the first then goes on to 0.12 s in its folder
BRANCH = scene("500") + """local sim = drive:start { out = "out/drive", progress = false }
sim:run_to(0.05)
local ck = sim:save("ck/mid.ckpt")
sim:wet { from = 0, to = 0.3, mu = 0.2 }
sim:run_to(0.1)
local other = beltsim.resume(ck, { out = "out/branch", progress = false })
other:wet { from = 0, to = 0.3, mu = 0.05 }
other:run_to(0.1)
other:close()
sim:run_to(0.12)
sim:close()
"""

# the trial's periodic checkpoints: sim:save in an every callback (refused, "not inside a callback")
EVERY_SAVE = scene("500") + """local sim = drive:start { out = "out/every", progress = false }
local k = 0
sim:every(0.05, function(s) k = k + 1; print(s:save(string.format("ck/p%02d.ckpt", k))) end)
sim:run_to(0.2)
sim:close()
"""

LUA_LAW = """
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0, 0}, radius = 0.1, torque = beltsim.ramp(0.1, -40) },
    { name = "driven", centre = {0.29, 0}, radius = 0.1,
      torque = function(t, w) return -0.955 * w end },
  },
  belt = { elements = 60, pretension = 500 },
}
local save = beltsim.args.save ~= false
local sim = drive:start { progress = false }
sim:run_to(0.01)
if save then print(sim:save("late.ckpt")) end
sim:close()
"""


def run(args, cwd):
    p = subprocess.run([BELTSIM] + args, capture_output=True, text=True, cwd=cwd, timeout=300)
    return p.returncode, p.stdout, p.stderr


def warnings(err):
    """the lines of stderr but the scene's defaults"""
    return [line for line in err.splitlines() if "scene defaults" not in line and "bending" not in line]


def digest(folder):
    """each file of a folder and the hash of its bytes"""
    d = {}
    for n in sorted(os.listdir(folder)):
        if os.path.isfile(os.path.join(folder, n)):
            with open(os.path.join(folder, n), "rb") as f:
                d[n] = hashlib.sha256(f.read()).hexdigest()
    return d


def csv_bytes(ckpt):
    with open(ckpt) as f:
        return int(re.search(r"^csv_bytes (\d+)$", f.read(), re.M).group(1))


class Resume(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_resume_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        for name, text in (("drive.lua", DRIVE), ("resume.lua", RESUME), ("law.lua", LUA_LAW),
                           ("events.lua", EVENTS), ("slow_resume.lua", SLOW_RESUME), ("every_save.lua", EVERY_SAVE),
                           ("branch.lua", BRANCH)):
            with open(os.path.join(self.dir, name), "w") as f:
                f.write(text)

    def test_a_later_run_into_the_folder_is_not_spliced_to_the_checkpoints(self):
        out = os.path.join(self.dir, "out", "drive")
        code, _, err = run(["run", "drive.lua", "--set", "save=true"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(warnings(err), [])
        cut = csv_bytes(os.path.join(out, "mid.ckpt"))
        # the same script again, another pretension (530.34 N: its rows end at the byte where the
        # 500 N run's checkpoint cuts, so that only the rows' contents tell the runs apart)
        code, _, err = run(["run", "drive.lua", "--set", "pretension=530.34"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(warnings(err), [
            "beltsim: warning: the output folder out/drive holds an earlier run's checkpoint mid.ckpt: this run "
            "replaces the outputs it continues, so beltsim.resume will refuse it unless this run saves its own over "
            "it (give each run its own --out or out = ..., or remove it)"])
        with open(os.path.join(out, "timeseries.csv"), "rb") as f:
            series = f.read()
        coincide = len(series) >= cut and series[cut - 1:cut] == b"\n"
        before = digest(out)
        code, _, err = run(["run", "resume.lua", "--set", "ck=out/drive/mid.ckpt"], self.dir)
        self.assertEqual(code, 1, err)
        self.assertEqual(digest(out), before)  # nothing changed
        if not coincide:  # (another machine's numbers: refused by the rows' ends already)
            self.assertIn("beltsim.resume: out/drive/mid.ckpt: ", err)
            self.skipTest("the 530.34 N run's rows do not end at the checkpoint's byte on this machine")
        self.assertEqual(warnings(err), [
            "beltsim: resume.lua:2: beltsim.resume: out/drive/mid.ckpt: the outputs in %s are not the ones this "
            "checkpoint's run wrote: parameters.csv (its first %d bytes, the parameters the checkpoint's run wrote "
            "at its start, differ) and timeseries.csv (its first %d bytes, to t = 0.1 s, are not the ones the "
            "checkpoint's run wrote). Another run has written the folder since the checkpoint was saved, and "
            "continuing would join this checkpoint's run to that run's rows. Nothing was changed: resume a "
            "checkpoint the later run saved, or run the script that saved this one again (each run its own "
            "folder: --out or out = ...)" % ("out/drive", self.parameters_bytes(out), cut)])
        # the checkpoint's own run back in the folder: it resumes
        self.assertEqual(run(["run", "drive.lua"], self.dir)[0], 0)
        code, _, err = run(["run", "resume.lua", "--set", "ck=out/drive/mid.ckpt"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("beltsim: out/drive/mid.ckpt resumed at t = 0.1 s", err)

    def test_a_resumed_simulation_has_a_wall_time_limit(self):
        # a checkpoint does not keep max_wall: --max-wall (every run's) and beltsim.resume's own give
        # the resumed simulation one (it had none, and --max-wall was said not to reach it)
        code, _, err = run(["run", "drive.lua", "--set", "save=true"], self.dir)
        self.assertEqual(code, 0, err)
        for args in (["--max-wall", "0.5"], ["--set", "max_wall=0.5"], ["--set", "max_wall=100", "--max-wall", "0.5"]):
            code, _, err = run(["run", "slow_resume.lua", "--set", "ck=out/drive/mid.ckpt"] + args, self.dir)
            self.assertEqual(code, 1, err)
            self.assertNotIn("applies to scene:run and scene:start only", err)
            # the limit named where it was given
            given = "--max-wall 0.5 s" if "--max-wall" in args else "max_wall = 0.5 s"
            stopped = (re.escape("beltsim: slow_resume.lua:5: sim:run_to: stopped at its wall-time limit (%s) at t = "
                                 % given) + r"0\.1[0-9]* s of 0\.2 s; the outputs up to then are in ")
            self.assertRegex(warnings(err)[-1], stopped, args)
        # refused as scene:start's max_wall is
        code, _, err = run(["run", "slow_resume.lua", "--set", "ck=out/drive/mid.ckpt", "--set", "max_wall=0"],
                           self.dir)
        self.assertEqual(code, 1, err)
        self.assertEqual(warnings(err), ["beltsim: slow_resume.lua:3: beltsim.resume.max_wall: must be > 0 s and "
                                         "finite (got 0 s)"])

    def test_checkpoints_saved_by_a_callback_resume_bit_for_bit(self):
        # written once everything due at the callback's time is done: resumed, each continues as the
        # run that went on (sim_test's Live.ACheckpointACallbackAsksForResumesBitForBit: when's too)
        code, out, err = run(["run", "every_save.lua"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out.split(), ["out/every/ck/p%02d.ckpt" % k for k in range(1, 5)])
        series = os.path.join(self.dir, "out", "every", "timeseries.csv")
        with open(series, "rb") as f:
            whole = f.read()
        for k in (1, 2, 3):
            code, _, err = run(["run", "resume.lua", "--set", "ck=out/every/ck/p%02d.ckpt" % k], self.dir)
            self.assertEqual(code, 0, err)
            self.assertIn("resumed at t = %g s" % (0.05 * k), err)
            with open(series, "rb") as f:
                self.assertEqual(f.read(), whole, k)

    def parameters_bytes(self, out):
        with open(os.path.join(out, "mid.ckpt")) as f:
            return int(re.search(r"^parameters_bytes (\d+)$", f.read(), re.M).group(1))

    def test_a_folder_moved_away_is_refused_and_not_made_again(self):
        code, _, err = run(["run", "drive.lua", "--set", "save=true", "--set", "t_end=0.11", "--set", "out=out/ck"],
                           self.dir)
        self.assertEqual(code, 0, err)
        os.rename(os.path.join(self.dir, "out", "ck"), os.path.join(self.dir, "out", "ck_archive"))
        code, _, err = run(["run", "resume.lua", "--set", "ck=out/ck_archive/mid.ckpt"], self.dir)
        self.assertEqual(code, 1, err)
        # (named as the run names its folder: relative to where beltsim runs, which holds them)
        folder, archive = "out/ck", "out/ck_archive"
        self.assertEqual(warnings(err), [
            "beltsim: resume.lua:2: beltsim.resume: out/ck_archive/mid.ckpt: the run's output folder %s, whose "
            "files this checkpoint continues, is not there (%s, where the checkpoint lies, holds a timeseries.csv: "
            "if it is that folder moved, move it back to %s): put the run's folder back where it was to resume it, "
            "or run the scene again; nothing was written" % (folder, archive, folder)])
        self.assertEqual(sorted(os.listdir(os.path.join(self.dir, "out"))), ["ck_archive"])
        # moved back, it resumes
        os.rename(os.path.join(self.dir, archive), os.path.join(self.dir, folder))
        code, _, err = run(["run", "resume.lua", "--set", "ck=out/ck/mid.ckpt"], self.dir)
        self.assertEqual(code, 0, err)

    def test_a_resumed_run_leaves_one_set_of_end_rows(self):
        # docs/outputs.md's recipe (a stopped run continued into its folder) left parameters.csv with
        # the stopped run's end rows (end.status interrupted) and then the continuation's (ok): a
        # lookup by name found two. The continuation cuts the file back to the rows its run wrote
        # at its start, and its own end rows follow once
        out = os.path.join(self.dir, "out", "drive")
        code, _, err = run(["run", "drive.lua", "--set", "save=true", "--set", "t_end=0.15"], self.dir)
        self.assertEqual(code, 0, err)
        with open(os.path.join(out, "parameters.csv"), "rb") as f:
            first = f.read()
        code, _, err = run(["run", "resume.lua", "--set", "ck=out/drive/mid.ckpt"], self.dir)
        self.assertEqual(code, 0, err)
        with open(os.path.join(out, "parameters.csv"), "rb") as f:
            raw = f.read()
        text = raw.decode()
        names = [line.split(",", 1)[0] for line in text.splitlines()]
        for name in ["end.status", "end.t", "end.last_row_t", "warning.failed_step.count"]:
            self.assertEqual(names.count(name), 1, name + " in:\n" + text)
        self.assertTrue(text.endswith("\n"))
        self.assertIn("\nend.t,0.2,s,", text)
        self.assertNotIn("\nend.t,0.15,", text)
        start = self.parameters_bytes(out)  # (bytes: the notes hold N·m)
        self.assertEqual(raw[:start], first[:start])
        self.assertTrue(raw[start:].startswith(b"warning."), raw[start:start + 80])

    def test_the_outputs_at_a_changes_time_show_the_run_after_it(self):
        # a trial's row at t = 0.3 of beltsim.step(0.3, from, to) had the `from` torque, and its row
        # at a wet event's 0.5 s the dry belt, while events.csv dated the event 0.5: the changes at
        # a time now come before its outputs. A state kept there (frames at those times) holds the
        # run after the change too: resumed, it went on without the event, which was still ahead
        # in it at a time its resume took as past
        out = os.path.join(self.dir, "out", "events")
        code, _, err = run(["run", "events.lua"], self.dir)
        self.assertEqual(code, 0, err)
        with open(os.path.join(out, "timeseries.csv")) as f:
            rows = {r["t"]: r for r in csv.DictReader(f)}
        self.assertEqual([rows[t]["driven.torque"] for t in ("0.009", "0.01", "0.011")], ["0", "3", "3"])
        # the means over (t - 0.001, t]: the step's value before it up to 0.01, its value after from there
        self.assertEqual([round(float(rows[t]["driven.torque_mean"]), 12) for t in ("0.01", "0.011")], [0, 3])
        self.assertEqual([round(float(rows[t]["driver.mu"]), 12) for t in ("0.019", "0.02", "0.021")], [1, 0.2, 0.2])
        with open(os.path.join(out, "events.csv")) as f:
            self.assertIn("\n0.02,set_mu,", f.read())
        with open(os.path.join(out, "timeseries.csv"), "rb") as f:
            series = f.read()
        for state in ("state_00003.ckpt", "state_00006.ckpt"):  # at 0.01 s and 0.02 s
            code, _, err = run(["run", "resume.lua", "--set", "ck=out/events/states/" + state], self.dir)
            self.assertEqual(code, 0, err)
            with open(os.path.join(out, "timeseries.csv"), "rb") as f:
                self.assertEqual(f.read()[:len(series)], series, state)
            with open(os.path.join(out, "events.csv")) as f:
                self.assertEqual(f.read().count(",set_mu,"), 1, state)

    def test_a_checkpoint_branches_into_a_folder_of_its_own(self):
        # trial 22: the folder-in-use refusal advised out = ..., which beltsim.resume refused as an
        # unknown key, and the only second branch from a checkpoint was rewind = true, which cut the
        # first branch's rows. With out, the checkpoint's outputs up to it are copied into the new
        # folder and the run goes on there; the first simulation's folder is read, never written
        code, _, err = run(["run", "branch.lua"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("beltsim: out/drive/ck/mid.ckpt resumed at t = 0.05 s; its outputs go on in out/branch (a copy "
                      "of out/drive's up to it; that folder is left as it is)\n", err)
        first, branch = os.path.join(self.dir, "out", "drive"), os.path.join(self.dir, "out", "branch")
        with open(os.path.join(first, "timeseries.csv")) as f:
            rows = f.read().splitlines()
        with open(os.path.join(branch, "timeseries.csv")) as f:
            other = f.read().splitlines()
        # the first branch whole, to 0.12 s; the second the same rows to 0.05 s, its own after them
        self.assertEqual((rows[-1].split(",")[0], other[-1].split(",")[0]), ("0.12", "0.1"))
        self.assertEqual(other[:52], rows[:52])
        self.assertNotEqual(other[60], rows[60])
        with open(os.path.join(first, "events.csv")) as f:
            self.assertEqual(f.read(), 't,what,value\n0.05,wet,"mu = 0.2 on s in [0, 0.3] m"\n')
        with open(os.path.join(branch, "events.csv")) as f:
            self.assertEqual(f.read(), 't,what,value\n0.05,resume,out/drive/ck/mid.ckpt\n'
                                       '0.05,wet,"mu = 0.05 on s in [0, 0.3] m"\n')
        with open(os.path.join(branch, "parameters.csv")) as f:
            params = f.read()
        self.assertIn("\nrun.out,out/branch,", params)
        self.assertIn("\nend.t,0.1,s,", params)
        with open(os.path.join(first, "parameters.csv")) as f:
            self.assertIn("\nend.t,0.12,s,", f.read())
        # a branch into the checkpoint's own folder is refused before anything is touched (trial 25:
        # the plain resume's refusal there advised rewind, which cut the first run)
        before = {n: open(os.path.join(first, n), "rb").read() for n in ("timeseries.csv", "events.csv")}
        for out in ("out/drive", "out/drive/", "./out/drive"):
            with open(os.path.join(self.dir, "into.lua"), "w") as f:
                f.write('beltsim.resume("out/drive/ck/mid.ckpt", { out = "%s", progress = false })\n' % out)
            code, _, err = run(["run", "into.lua"], self.dir)
            self.assertEqual(code, 1, err)
            self.assertIn("out/drive/ck/mid.ckpt: out = %s is the checkpoint's own output folder, out/drive: a branch "
                          "goes into a folder of its own (resume without out to go on in that folder)" % out, err)
        self.assertEqual(before, {n: open(os.path.join(first, n), "rb").read() for n in before})

    def test_a_lua_law_is_named_at_save_only(self):
        code, out, err = run(["run", "law.lua"], self.dir)
        self.assertEqual((code, out), (1, ""), err)
        self.assertEqual(warnings(err), [
            "beltsim: law.lua:13: sim:save: pulley 'driven'.torque (function at law.lua:6) is Lua code, which a "
            "checkpoint cannot hold: give the law as a table (constant, per_speed, ramps, sines, ...) to save this "
            "simulation"])
        # never saved: not a word of checkpoints
        code, out, err = run(["run", "law.lua", "--set", "save=false"], self.dir)
        self.assertEqual((code, out), (0, ""), err)
        self.assertEqual(warnings(err), [])

if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
