#!/usr/bin/env python3
"""keep_states = true: a run keeps its whole state at each frame time (OUT/states/state_NNNNN.ckpt,
NNNNN the frame's number), with or without frames, and `beltsim render` draws them after the run:
a folder of states to PNGs (each the same picture as the run's frame at that time) or to a video
(one frame per state), each state read once, the options' and the states' checks."""
import os
import ctypes
import re
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import unittest
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None


# frames every 1/300 s up to 0.02 s: frames 0..6, and a state kept at each
KEEP = two_pulley(40, inertia=0.025) + """
drive:run { t_end = 0.02, progress = false, out = "out", integrator = "esdirk32", keep_states = true,
  frames = { fps = 30, slowdown = 10, size = {320, 180}, quantity = "tension", range = {0, 1000},
             magnify = 20, png = true, video = false } }
"""


class OpenWatch:
    """counts the openings of each file in a folder while it watches (inotify's IN_OPEN, through
    libc: no tool to install)"""
    IN_OPEN, IN_NONBLOCK = 0x20, os.O_NONBLOCK

    def __init__(self, folder):
        self.libc = ctypes.CDLL(None, use_errno=True)
        self.fd = self.libc.inotify_init1(self.IN_NONBLOCK)
        if self.fd < 0 or self.libc.inotify_add_watch(self.fd, os.fsencode(folder), self.IN_OPEN) < 0:
            raise OSError(ctypes.get_errno(), "inotify on " + folder)

    def counts(self):
        """{file name: openings} since the watch began (the folder's own openings left out); ends the watch"""
        data = b""
        while True:
            try:
                data += os.read(self.fd, 65536)
            except BlockingIOError:
                break
        os.close(self.fd)
        counts, at = {}, 0
        while at < len(data):
            _, mask, _, size = struct.unpack_from("iIII", data, at)
            name = data[at + 16:at + 16 + size].rstrip(b"\0").decode()
            at += 16 + size
            if name and mask & self.IN_OPEN:
                counts[name] = counts.get(name, 0) + 1
        return counts


def run(args, cwd):
    p = subprocess.run([BELTSIM] + args, capture_output=True, text=True, cwd=cwd, timeout=120)
    return p.returncode, p.stdout, p.stderr


def state_time(path):
    """the time a checkpoint holds (its 'now' line)"""
    with open(path) as f:
        for line in f:
            if line.startswith("now "):
                return float(line.split()[1])
    raise AssertionError(path + " has no 'now' line")


def frame_times(t_start, dt, t_end):
    """the frame schedule's times up to t_end, as the run computes them (t_start + k·dt)"""
    out, k = [], 0
    while t_start + k * dt <= t_end:
        out.append(t_start + k * dt)
        k += 1
    return out


class KeepStates(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="beltsim_keep_")
        cls.addClassCleanup(shutil.rmtree, cls.dir, True)  # also when this fails
        cls.script("keep.lua", KEEP)
        code, out, err = run(["run", "keep.lua"], cls.dir)
        assert code == 0, err
        cls.states = os.path.join(cls.dir, "out", "states")

    @classmethod
    def script(cls, name, text):
        with open(os.path.join(cls.dir, name), "w") as f:
            f.write(text)

    def listing(self, folder):
        return sorted(os.listdir(os.path.join(self.dir, folder)))

    def test_one_state_per_frame_time(self):
        frames = self.listing(os.path.join("out", "frames"))
        self.assertEqual(frames, ["frame_%05d.png" % k for k in range(7)])
        self.assertEqual(self.listing(os.path.join("out", "states")), ["state_%05d.ckpt" % k for k in range(7)])
        self.assertEqual([state_time(os.path.join(self.states, "state_%05d.ckpt" % k)) for k in range(7)],
                         frame_times(0.0, 1.0 / (30.0 * 10.0), 0.02))

    def test_each_kept_state_draws_the_runs_frame_at_its_time(self):
        code, out, err = run(["render", os.path.join("out", "states"), "--out", "pngs"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out.split(), [os.path.join("pngs", "state_%05d.png" % k) for k in range(7)])
        for k in range(7):
            code, out, err = run(["compare", os.path.join("pngs", "state_%05d.png" % k),
                                  os.path.join("out", "frames", "frame_%05d.png" % k)], self.dir)
            self.assertEqual(code, 0, "state %d: %s" % (k, out + err))
            self.assertIn("largest difference 0 levels", out)
        # one state alone, as a golden test renders it
        code, out, err = run(["render", os.path.join("out", "states", "state_00004.ckpt"), "--out", "k4.png"],
                             self.dir)
        self.assertEqual((code, out), (0, "k4.png\n"), err)
        self.assertEqual(run(["compare", "k4.png", os.path.join("out", "frames", "frame_00004.png")], self.dir)[0], 0)
        self.assertEqual(run(["compare", "k4.png", os.path.join("out", "frames", "frame_00005.png")], self.dir)[0], 1)

    def test_each_state_is_read_once(self):
        # a render of several states reads each once, to check it and to draw it (each but the
        # first was read twice), to PNGs and to a video alike
        for out in (["--out", "once"], ["--video", "once.mp4"]):
            watch = OpenWatch(self.states)
            code, _, err = run(["render", os.path.join("out", "states")] + out, self.dir)
            self.assertEqual(code, 0, err)
            self.assertEqual(watch.counts(), {"state_%05d.ckpt" % k: 1 for k in range(7)}, out)

    def test_the_states_make_a_video_with_a_frame_each(self):
        code, out, err = run(["render", os.path.join("out", "states"), "--video", "v.mp4", "--size", "640x360",
                              "--quantity", "slip"], self.dir)
        self.assertEqual((code, out), (0, "v.mp4\n"), err)
        r = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames,width,height", "-of", "csv=p=0",
                            os.path.join(self.dir, "v.mp4")], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.strip(), "640,360,7")
        # several files, in the order given
        files = [os.path.join("out", "states", "state_%05d.ckpt" % k) for k in (6, 0, 3)]
        code, out, err = run(["render"] + files + ["--video", "three.mp4", "--out", "three"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out.split(), [os.path.join("three", "state_%05d.png" % k) for k in (6, 0, 3)] + ["three.mp4"])
        r = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames", "-of", "csv=p=0", os.path.join(self.dir, "three.mp4")],
                           capture_output=True, text=True)
        self.assertEqual(r.stdout.strip(), "3", r.stderr)

    def test_a_stopped_render_keeps_its_frames_apart(self):
        # Ctrl-C or SIGTERM ended `render --video` at once: an earlier video of the name was left
        # with no frame, a new one cut at its last whole second under the name asked for (a user
        # trial). It stops between two states: the video of those drawn plays, named
        # <stem>.partial.mp4, and the earlier video is left as it was
        many = os.path.join(self.dir, "many")
        os.makedirs(many, exist_ok=True)
        for k in range(300):
            shutil.copy(os.path.join(self.states, "state_00006.ckpt"), os.path.join(many, "state_%05d.ckpt" % k))
        for sig, status, said in [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")]:
            name = "stopped_%d" % sig
            with open(os.path.join(self.dir, name + ".mp4"), "wb") as f:
                f.write(b"an earlier video")
            p = subprocess.Popen([BELTSIM, "render", "many", "--out", name, "--video", name + ".mp4", "--size",
                                  "640x360"], cwd=self.dir, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))  # as a terminal's
            pngs = os.path.join(self.dir, name)
            deadline = time.monotonic() + 60
            while not os.path.exists(os.path.join(pngs, "state_00002.png")):
                self.assertIsNone(p.poll(), "the render ended before its third state")
                self.assertLess(time.monotonic(), deadline, "no third state drawn")
                time.sleep(0.01)
            p.send_signal(sig)
            out, err = p.communicate(timeout=30)
            self.assertEqual(p.returncode, status, err)
            drawn = len([n for n in os.listdir(pngs) if n.endswith(".png")])
            self.assertLess(drawn, 300, err)
            self.assertIn("beltsim render: the video of the %d of 300 states drawn is %s.partial.mp4 (it plays to its "
                          "last frame; %s.mp4 is left as it was)\n" % (drawn, name, name), err)
            self.assertIn("beltsim: %s; the outputs written so far are kept\n" % said, err)
            self.assertTrue(out.endswith(name + ".partial.mp4\n"), out)
            with open(os.path.join(self.dir, name + ".mp4"), "rb") as f:
                self.assertEqual(f.read(), b"an earlier video")
            r = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                                "stream=nb_read_frames", "-of", "csv=p=0",
                                os.path.join(self.dir, name + ".partial.mp4")], capture_output=True, text=True)
            self.assertEqual((r.stdout.strip(), r.stderr), (str(drawn), ""))
        # a render that ends replaces the earlier video whole, and leaves no partial one
        code, out, err = run(["render", os.path.join("out", "states"), "--video", "stopped_2.mp4"], self.dir)
        self.assertEqual((code, out), (0, "stopped_2.mp4\n"), err)
        with open(os.path.join(self.dir, "stopped_2.mp4"), "rb") as f:
            self.assertNotEqual(f.read(), b"an earlier video")

    def test_states_without_frames_at_the_frame_times(self):
        # no frames: the default frame settings' times (fps 30, slowdown 10: every 1/300 s)
        self.script("bare.lua", two_pulley(40, inertia=0.025) + 'drive:run { t_end = 0.01, progress = false, out = "bare", '
                                             'keep_states = true }\n')
        code, out, err = run(["run", "bare.lua"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(self.listing("bare"), ["events.csv", "parameters.csv", "states",
                                                "timeseries.csv", "timeseries_units.csv"])
        names = self.listing(os.path.join("bare", "states"))
        self.assertEqual([state_time(os.path.join(self.dir, "bare", "states", n)) for n in names],
                         frame_times(0.0, 1.0 / 300.0, 0.01))
        # frames that draw nothing give the times: every 1/150 s from 0.004 s
        self.script("times.lua", two_pulley(40, inertia=0.025) + 'drive:run { t_end = 0.02, progress = false, out = "times", '
                                              'keep_states = true, frames = { slowdown = 5, t_start = 0.004 } }\n')
        code, out, err = run(["run", "times.lua"], self.dir)
        self.assertEqual(code, 0, err)
        names = self.listing(os.path.join("times", "states"))
        times = frame_times(0.004, 1.0 / 150.0, 0.02)
        self.assertEqual(names, ["state_%05d.ckpt" % k for k in range(len(times))])
        self.assertEqual([state_time(os.path.join(self.dir, "times", "states", n)) for n in names], times)
        # --no-frames draws nothing and keeps the states at the frames' times
        code, out, err = run(["run", "keep.lua", "--no-frames", "--out", "nf"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertNotIn("frames", self.listing("nf"))
        self.assertEqual(self.listing(os.path.join("nf", "states")), self.listing(os.path.join("out", "states")))

    def test_bad_settings(self):
        for name, run_keys, message in [
                ("b1.lua", "keep_states = 1", "run.keep_states: boolean expected, got number 1"),
                ("b2.lua", 'keep_states = true, integrator = "cvode"',
                 "keep_states: cvode keeps a multistep history that SUNDIALS cannot export"),
                ("b3.lua", "frames = { slowdown = 5 }", "neither png nor video asked for"),
                ("b4.lua", "keep_states = true, t_end = 400", "would keep 120000 states; the limit is 100000")]:
            run_keys = run_keys if "t_end" in run_keys else run_keys + ", t_end = 0.01"
            self.script(name, two_pulley(40, inertia=0.025) + 'drive:run { progress = false, out = "%s", %s }\n' % (name, run_keys))
            code, out, err = run(["run", name], self.dir)
            self.assertEqual(code, 1, name + err)
            self.assertIn(message, err)
            self.assertIn(name + ":", err)

    def test_a_lua_law_is_refused_before_anything_is_written(self):
        # a kept state is a checkpoint, which holds no Lua code: refused naming keep_states, with
        # no t = 0 row, frame or states/ written (the first kept state had failed after they were)
        lua_law = two_pulley(40, inertia=0.025).replace("torque = { per_speed = -0.955 }",
                                                         "torque = function(t, w) return -0.955 * w end")
        self.script("lua_law.lua", lua_law + 'drive:run { t_end = 0.01, progress = false, out = "lua_law", '
                                             'keep_states = true, frames = { png = true } }\n')
        code, out, err = run(["run", "lua_law.lua"], self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("lua_law.lua:9: keep_states: pulley driven's torque law is Lua code (function at lua_law.lua:5), "
                      "which a kept state (a checkpoint) cannot hold", err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "lua_law")), self.listing("lua_law")
                         if os.path.exists(os.path.join(self.dir, "lua_law")) else "")
        # a law set to Lua code while such a run goes on: refused, the drive unchanged
        self.script("set_law.lua", two_pulley(40, inertia=0.025) + 'local sim = drive:start { progress = false, '
                    'out = "set_law", keep_states = true }\nsim:run_to(0.004)\n'
                    'sim:set_torque("driven", function(t, w) return 0 end)\n')
        code, out, err = run(["run", "set_law.lua"], self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("set_law.lua:11: ", err)
        self.assertIn("keep_states: pulley driven's torque law is Lua code (function at set_law.lua:11)", err)
        with open(os.path.join(self.dir, "set_law", "events.csv")) as f:
            self.assertNotIn("driven.torque", f.read())

    def test_bad_render_usage_and_states(self):
        code, out, err = run(["render", os.path.join("out", "states")], self.dir)
        self.assertEqual(code, 2)
        self.assertIn("--out is required (the PNG, or a folder for several states), or --video MP4", err)
        code, out, err = run(["render", os.path.join("out", "states"), "--out", "x", "--fps", "5"], self.dir)
        self.assertEqual(code, 2)
        self.assertIn("render does not take: --fps", err)
        os.makedirs(os.path.join(self.dir, "empty"), exist_ok=True)
        code, out, err = run(["render", "empty", "--out", "x"], self.dir)
        self.assertEqual((code, err), (1, "beltsim render: empty: no states in it (no *.ckpt files)\n"))
        # a state of another scene (80 elements) among them: refused before anything is written (the
        # PNGs before it were left, and a video of one frame)
        self.script("other.lua", two_pulley(80, inertia=0.025) + 'drive:run { t_end = 0.001, progress = false, out = "other", '
                                              'keep_states = true }\n')
        self.assertEqual(run(["run", "other.lua"], self.dir)[0], 0)
        first = os.path.join("out", "states", "state_00000.ckpt")
        other = os.path.join("other", "states", "state_00000.ckpt")
        code, out, err = run(["render", first, other, "--out", "mixed", "--video", "mixed.mp4"], self.dir)
        self.assertEqual(code, 1)
        self.assertEqual(err, "beltsim render: %s: a state of another scene than %s's (its belt.elements differs; one "
                              "render draws the states of one scene)\n" % (other, first))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "mixed")))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "mixed.mp4")))


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
