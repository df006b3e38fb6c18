#!/usr/bin/env python3
"""`beltsim render CHECKPOINT --out PNG`: the state a checkpoint holds drawn by the renderer of a
run's frames (the same picture as the run's frame at that time), the same bytes twice, another
picture for another quantity, the options' checks, and a checkpoint's outputs left untouched."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None

# a run that draws a frame every 1/300 s (frame 6 at t = 0.02 s) and saves a checkpoint there
SCENE = two_pulley(40, inertia=0.025) + """local sim = drive:start { progress = false, out = "out", integrator = "esdirk32",
  frames = { fps = 30, slowdown = 10, size = {320, 180}, quantity = "tension", range = {0, 1000},
             magnify = 20, png = true, video = false } }
sim:run_to(0.02)
sim:save("state.txt")
sim:close()
"""


def run(args, cwd):
    p = subprocess.run([BELTSIM] + args, capture_output=True, text=True, cwd=cwd, timeout=120)
    return p.returncode, p.stdout, p.stderr


class Render(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="beltsim_render_")
        cls.addClassCleanup(shutil.rmtree, cls.dir, True)  # also when this fails
        with open(os.path.join(cls.dir, "s.lua"), "w") as f:
            f.write(SCENE)
        code, out, err = run(["run", "s.lua"], cls.dir)
        assert code == 0, err
        cls.checkpoint = os.path.join(cls.dir, "out", "state.txt")
        assert os.path.exists(cls.checkpoint), err

    def render(self, *args):
        return run(["render", self.checkpoint] + list(args), self.dir)

    def bytes(self, name):
        with open(os.path.join(self.dir, name), "rb") as f:
            return f.read()

    def test_the_picture_is_the_runs_frame_at_that_time(self):
        code, out, err = self.render("--out", "a.png")
        self.assertEqual((code, out), (0, "a.png\n"), err)
        code, out, err = run(["compare", "a.png", os.path.join("out", "frames", "frame_00006.png")], self.dir)
        self.assertEqual(code, 0, out + err)
        self.assertIn("largest difference 0 levels", out)

    def test_the_same_bytes_twice(self):
        self.assertEqual(self.render("--out", "1.png")[0], 0)
        self.assertEqual(self.render("--out", "2.png")[0], 0)
        self.assertEqual(self.bytes("1.png"), self.bytes("2.png"))

    def test_quantity_size_and_view_change_the_picture(self):
        self.assertEqual(self.render("--out", "tension.png")[0], 0)
        code, out, err = self.render("--out", "friction.png", "--quantity", "friction")
        self.assertEqual(code, 0, err)
        code, out, err = run(["compare", "friction.png", "tension.png"], self.dir)
        self.assertEqual(code, 1, out + err)
        self.assertNotEqual(self.bytes("friction.png"), self.bytes("tension.png"))
        code, out, err = self.render("--out", "big.png", "--size", "640x360")
        self.assertEqual(code, 0, err)
        code, out, err = run(["compare", "big.png", "tension.png"], self.dir)
        self.assertEqual(out, "differ: the sizes differ: big.png is 640x360, tension.png is 320x180\n")
        code, out, err = self.render("--out", "zoom.png", "--view", "0.29,0,0.3")
        self.assertEqual(code, 0, err)
        self.assertEqual(run(["compare", "zoom.png", "tension.png"], self.dir)[0], 1)

    def test_the_checkpoints_outputs_are_left_alone(self):
        csv = os.path.join(self.dir, "out", "timeseries.csv")
        events = os.path.join(self.dir, "out", "events.csv")
        before = (self.bytes(csv), self.bytes(events))
        self.assertEqual(self.render("--out", "x.png")[0], 0)
        self.assertEqual((self.bytes(csv), self.bytes(events)), before)

    def test_an_odd_size_for_a_png(self):
        code, out, err = self.render("--out", "odd.png", "--size", "321x181")
        self.assertEqual((code, out), (0, "odd.png\n"), err)
        with open(os.path.join(self.dir, "odd.png"), "rb") as f:
            head = f.read(24)
        self.assertEqual((int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")), (321, 181))

    def test_a_size_too_small_for_the_text_is_said_once(self):
        # a 161x91 frame cut its header and left its legend out without a word (a user trial): drawn, with a warning
        code, out, err = self.render("--out", "tiny.png", "--size", "161x91")
        self.assertEqual((code, out), (0, "tiny.png\n"), err)
        self.assertEqual(err.count("warning"), 1, err)
        self.assertIn("beltsim render: warning: --size 161x91 is too small for the frame's text with every line of its "
                      "legend (", err)
        self.assertIn(" is the smallest of its shape that shows it all; the frames are drawn as they are\n", err)
        # the header quoted is the state's, drawn at t = 0.02 s (it quoted one of t = 0.0000 s: a user trial)
        code, out, err = self.render("--out", "header.png", "--size", "260x146", "--quantity", "slip")
        self.assertEqual(code, 0, err)
        self.assertIn("legend ('t = 0.0200 s      colour: slip velocity [m/s]", err)
        self.assertEqual(self.render("--out", "fits.png", "--size", "640x360"), (0, "fits.png\n", ""))
        # a run's frames: said once, as the run starts
        with open(os.path.join(self.dir, "tiny.lua"), "w") as f:
            f.write(SCENE.replace("size = {320, 180}", "size = {161, 91}").replace('out = "out"', 'out = "tiny"'))
        code, out, err = run(["run", "tiny.lua"], self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(err.count("beltsim: warning: frames.size 161x91 is too small for the frame's text"), 1, err)
        self.assertTrue(os.path.isfile(os.path.join(self.dir, "tiny", "frames", "frame_00006.png")))

    def test_a_name_ending_in_a_slash_is_a_folder(self):
        # one state with --out DIR/: DIR/<state name>.png (it wrote a PNG file named DIR)
        code, out, err = self.render("--out", "pics_dir/")
        self.assertEqual((code, out), (0, os.path.join("pics_dir", "state.png") + "\n"), err)
        self.assertTrue(os.path.isfile(os.path.join(self.dir, "pics_dir", "state.png")))

    def test_several_states_need_a_folder_not_a_pictures_name(self):
        # several states with --out NAME.png made a folder NAME.png of PNGs: refused, nothing written
        code, out, err = run(["render", self.checkpoint, self.checkpoint, "--out", "pics/tension.png"], self.dir)
        self.assertEqual((code, out), (2, ""), err)
        self.assertIn("beltsim: --out pics/tension.png: 2 states need a folder for their PNGs (DIR/<state name>.png "
                      "each), and a name ending in .png is a picture's: give --out a folder, or one state file\n", err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "pics")))
        # a folder of states too, whatever it holds
        os.makedirs(os.path.join(self.dir, "one"), exist_ok=True)
        shutil.copy(self.checkpoint, os.path.join(self.dir, "one", "state_00006.ckpt"))
        code, out, err = run(["render", "one", "--out", "one.PNG"], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("--out one.PNG: the states of the folder one need a folder for their PNGs", err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "one.PNG")))
        code, out, err = run(["render", "one", "--out", "one_pngs"], self.dir)
        self.assertEqual((code, out), (0, os.path.join("one_pngs", "state_00006.png") + "\n"), err)

    def test_states_of_one_name_into_one_folder(self):
        # the same state of two runs made one PNG, the second drawn over the first: refused, nothing written
        for run_dir in ("r5", "r7"):
            os.makedirs(os.path.join(self.dir, run_dir), exist_ok=True)
            shutil.copy(self.checkpoint, os.path.join(self.dir, run_dir, "state_00006.ckpt"))
        r5, r7 = os.path.join("r5", "state_00006.ckpt"), os.path.join("r7", "state_00006.ckpt")
        code, out, err = run(["render", r5, r7, "--out", "both"], self.dir)
        self.assertEqual((code, out), (2, ""), err)
        self.assertIn("beltsim: --out both: %s and %s would both be drawn to %s (DIR/<state name>.png each, the "
                      "second over the first): render them into separate --out folders\n"
                      % (r5, r7, os.path.join("both", "state_00006.png")), err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "both")))
        # folders of states too
        code, out, err = run(["render", "r5", "r7", "--out", "both/"], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("would both be drawn to", err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "both")))
        code, out, err = run(["render", "r5", "--out", "both_r5"], self.dir)
        self.assertEqual((code, out), (0, os.path.join("both_r5", "state_00006.png") + "\n"), err)

    def test_bad_options_and_files(self):
        for args, message in [
                (["--out", "x.png", "--quantity", "tensoin"], "--quantity: unknown quantity 'tensoin' (did you mean "
                                                              "'tension'?)"),
                (["--out", "x.png", "--size", "640"], "--size needs WxH in pixels, e.g. 640x360, got '640'"),
                (["--out", "x.png", "--size", "16x8193"], "--size needs whole numbers of pixels in 16..8192"),
                # an odd size is a video's problem only (below: PNGs take it)
                (["--video", "x.mp4", "--size", "641x360"], "--size 641x360: width and height must be even for "
                                                            "--video (H.264 in yuv420p)"),
                # a picture is a PNG and a video an MP4: the bytes were written under any name
                (["--out", "pics.mp4"], "--out pics.mp4: beltsim draws PNG pictures: give a name ending in .png"),
                (["--video", "clip.png"], "--video clip.png: beltsim writes MP4 videos (H.264): give a name ending "
                                          "in .mp4"),
                (["--out", "x.png", "--view", "0,0"], "--view needs X,Y,WIDTH in metres"),
                # the option as typed, not the run's key (it read "frames.range: needs lo < hi (got {5, 1})")
                (["--out", "x.png", "--range", "5,1"], "beltsim: --range needs lo < hi, got '5,1'\n"),
                (["--out", "x.png", "--magnify", "-1"], "beltsim: --magnify must be in (0, 1e4], got '-1'\n"),
                (["--out", "x.png", "--view", "0,0,0"], "beltsim: --view: the width must be in [1e-6, 1e5] m, "
                                                        "got '0,0,0'\n"),
                (["--out", "x.png", "--rtol", "1e-3"], "render does not take: --rtol"),
                ([], "--out is required")]:
            code, out, err = self.render(*args)
            self.assertEqual(code, 2, args)
            self.assertIn(message, err)
            self.assertNotIn("frames.", err)
        for name in ("x.mp4", "pics.mp4", "clip.png"):
            self.assertFalse(os.path.exists(os.path.join(self.dir, name)), name)
        code, out, err = run(["render", "missing.txt", "--out", "x.png"], self.dir)
        self.assertEqual(code, 1)
        self.assertIn("beltsim render: missing.txt", err)
        code, out, err = run(["render", "s.lua", "--out", "x.png"], self.dir)
        self.assertEqual(code, 1)
        self.assertIn("beltsim render: s.lua", err)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
