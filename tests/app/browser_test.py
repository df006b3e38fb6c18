#!/usr/bin/env python3
"""The live view in a real browser (headless Chromium through selenium and chromium-driver, all
Debian): the page of a running dry scenario shows t advancing, Pause holds the run (the status says
where), a stretch dragged out on the picture fills the wet form with those elements' belt
coordinates and Wet lands it in events.csv, a torque set on the page lands in events.csv at that
time (the server's "queued" beside the controls cleared once the status says so), Continue lets
the run finish whole. The picture of the run paused at a run-to time asked for before the run began (t = 0.05 s,
so always the same state) is compared with tests/golden/live_page_frame.png by the goldens'
metric (`beltsim compare`, media/image_compare.hpp). Each step waits for what the page shows
(WebDriverWait, or the page's own script where WebDriver's round trips would be too slow), no
sleeps, each wait bounded far above what a loaded machine takes. Exit 77 (skipped) without selenium
or chromium-driver.

usage: browser_test.py BELTSIM [--update-golden]
  --update-golden (the target update_browser_golden): writes the golden picture and the README's
  screenshot of the page (media/live-view.png) instead of comparing; the screenshot is taken with
  the run taken on from the page to t = T_README, whatever the machine's speed
"""
import json
import os
import select
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.parse
import urllib.request
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

try:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.remote.remote_connection import RemoteConnection
    from selenium.webdriver.support.ui import Select, WebDriverWait
except ImportError:
    print("skipped: python3-selenium is not installed")
    sys.exit(77)

BELTSIM = None
UPDATE = False
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
GOLDEN = os.path.join(ROOT, "tests", "golden", "live_page_frame.png")
SCREENSHOT = os.path.join(ROOT, "media", "live-view.png")
T_SHOT = 0.05  # [s] the run-to time of the golden picture
# [s] the run-to time of the README's screenshot (--update-golden), asked for on the page after the
# stretch is wetted at T_SHOT: the wet stretch has come round to the driven pulley's wrap, which
# slips on all of it (about 5 m/s) while the driver speeds away from it, and the span tensions
# swing. The screenshot was taken where a pause clicked on the page had caught the run: a
# picture of the machine's speed, once the driver running away at -456 rad/s on the wet stretch
T_README = 0.26
# the columns the README's screenshot plots: the pulleys' speeds and the span tensions (the page's
# first choice), in a plot for each unit
README_COLUMNS = ["driver.omega", "driven.omega", "span_driver_driven.tension", "span_driven_driver.tension"]
# [s] the run goes on to T_README in steps of this, a run to t each: the page's plot gets the sample
# where each pauses, as well as those of the wall clock (20 a wall second): a plot as fine on a fast
# machine as on a slow one (the tensions swing with a period of about 9 ms; a fast machine's run
# from T_SHOT to T_README gave the plot 5 samples)
README_STEP = 1e-3
DRIVER = shutil.which("chromedriver")
T_END = 1.0  # [s] a few seconds of wall time: the page pauses the run before its end
# Bounds on a failure, not waits for timing: each step waits for what it needs to see, and these
# are far above what a 2-core machine at a load of 20 took (7 to 9 s for the run to T_SHOT and its
# picture, 12 to 19 s for Chromium's start, 3 to 13 s for the run's end)
WAIT = 60  # [s] at most for what the page should show
START = 120  # [s] at most for Chromium's start (chromedriver's own bound is 60 s)
COMMAND = 180  # [s] at most for one WebDriver command (selenium's own: none)
RUN = 120  # [s] at most for the run's end once it is let go
# [N·m] the torque set on the page: a load on the driven pulley, against its clockwise turning
# (counter-clockwise is positive); its value is not what is checked (it lands in events.csv at the
# paused time). -65 drove the driven pulley the way the driver does and the drive ran away to
# 1600 rad/s by T_END: the run on from the pause took 6.6 s of CPU where a load takes 1.05 s
LOAD = "65"


class Browser(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_browser_")
        if os.environ.get("BELTSIM_KEEP"):
            print("the test's files are kept in %s (BELTSIM_KEEP)" % self.dir, file=sys.stderr)
        else:
            self.addCleanup(shutil.rmtree, self.dir, True)
        # the run starts once the test has queued its run to T_SHOT (the file `go`): asked for after
        # the address is printed but with the run already going, the run to T_SHOT lost the race on
        # a loaded machine now and then (the run past T_SHOT, the page's request refused)
        self.go = os.path.join(self.dir, "go")
        with open(os.path.join(self.dir, "s.lua"), "w") as f:
            f.write(two_pulley(elements=40) + "while not io.open(%r) do os.execute('sleep 0.02') end\n" % self.go +
                    "drive:run { t_end = %r, sample = 1e-3 }\n" % T_END)
        # the browser first: its start (seconds) is not the run's time
        o = webdriver.ChromeOptions()
        o.add_experimental_option("browserStartupTimeout", START * 1000)  # [ms]
        for a in ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run",
                  "--user-data-dir=" + os.path.join(self.dir, "chromium"), "--window-size=1280,1800",
                  "--force-device-scale-factor=1", "--force-color-profile=srgb"]:
            o.add_argument(a)
        RemoteConnection.set_timeout(COMMAND)
        self.browser = webdriver.Chrome(service=Service(DRIVER), options=o)
        self.addCleanup(self.browser.quit)
        self.browser.set_script_timeout(WAIT)
        self.proc = subprocess.Popen([BELTSIM, "run", "s.lua", "--trusted", "--serve", "--out", "out"], cwd=self.dir,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        self.addCleanup(self.stop)
        self.url = self.address()

    def address(self):
        """the live view's address, from beltsim's first lines on stderr (within WAIT)"""
        end, err = time.monotonic() + WAIT, b""
        while True:
            at = err.find(b"live view at ")
            if at >= 0 and b"\n" in err[at:]:
                return err[at:].split(b"\n")[0][len(b"live view at "):].decode().strip()
            left = end - time.monotonic()
            if left <= 0 or not select.select([self.proc.stderr], [], [], left)[0]:
                self.fail("no address printed within %d s: %r" % (WAIT, err.decode()))
            chunk = os.read(self.proc.stderr.fileno(), 4096)
            if not chunk:
                self.fail("beltsim ended without printing its address: %r" % err.decode())
            err += chunk

    def stop(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        self.proc.stderr.close()

    def text(self, id_):
        return self.browser.find_element(By.ID, id_).text

    def value(self, id_):
        return self.browser.find_element(By.ID, id_).get_attribute("value")

    def check_legend(self, wait):
        """the legend names the checked columns, before and after a check box is changed, and no two
        shown series look alike (at least 60 levels apart in RGB: dygraphs' own hues gave
        driver.slip_speed and driven.omega 23 levels apart)"""
        b = self.browser

        def checked():  # one question to the browser (one for each box took 2 s at a load of 20)
            return b.execute_script("return Array.from(document.querySelectorAll('#columns input'))"
                                    ".filter(cb => cb.checked).map(cb => cb.dataset.column);")

        def legend():  # each plot's legend, one plot per unit
            return sorted(b.execute_script("return Array.from(document.querySelectorAll('#plots .legend'))"
                                           ".map(e => e.innerText).join(' ')").split())

        def per_plot():  # the shown columns of each plot and the plot's unit label
            return b.execute_script("return graphs.map(g => [g.getLabels().filter((c, k) => k > 0 && "
                                    "g.visibility()[k - 1]), g.getOption('ylabel')])")
        wait.until(lambda _: legend() == sorted(checked()) and len(checked()) > 3)
        # at first the pulleys' speeds and the span tensions, each unit in a plot of its own (on one
        # axis the tensions flattened the speeds into a line at zero: a user's trial)
        plots = per_plot()
        self.assertEqual([p[1] for p in plots], ["[rad/s]", "[N]"], plots)
        self.assertTrue(all(c.endswith(".omega") for c in plots[0][0]), plots)
        self.assertTrue(all(c.startswith("span_") and c.endswith(".tension") for c in plots[1][0]), plots)
        b.find_element(By.CSS_SELECTOR, "#columns input[data-column='driver.omega']").click()
        b.find_element(By.CSS_SELECTOR, "#columns input[data-column='driven.torque']").click()
        wait.until(lambda _: legend() == sorted(checked()))
        self.assertEqual([p[1] for p in per_plot()], ["[rad/s]", "[N·m]", "[N]"])
        self.assertNotIn("driver.omega", checked())
        self.assertIn("driven.torque", checked())

        def rgb(c):  # "#rrggbb" or "rgb(r,g,b)"
            if c.startswith("#"):
                return [int(c[k:k + 2], 16) for k in (1, 3, 5)]
            return [int(v) for v in c[c.index("(") + 1:-1].split(",")]
        colours = [rgb(c) for c in b.execute_script("return graphs.flatMap(g => g.getColors())")]
        names = checked()
        self.assertEqual(len(colours), len(names))
        for i in range(len(colours)):
            for j in range(i):
                d = sum((x - y) ** 2 for x, y in zip(colours[i], colours[j])) ** 0.5
                self.assertGreaterEqual(d, 60, (names[i], names[j], colours[i], colours[j]))

    def pick_stretch(self, wait):
        """drags on the paused picture from element 30 to element 3 of the 40 (past the belt's
        start at s = 0, the short way round): the form gets their s; a click off the belt fills
        nothing; Wet lands the stretch in events.csv at the paused time"""
        b, frame = self.browser, self.browser.find_element(By.ID, "frame")
        # where the renderer drew the elements in the picture the page shows (the same frame: its t)
        q = urllib.parse.urlsplit(self.url).query
        with urllib.request.urlopen(self.url.split("?")[0] + "frame.json?" + q, timeout=30) as r:
            placed = json.load(r)
        self.assertEqual(repr(placed["t"]), frame.get_attribute("data-t"))
        el = placed["elements"]
        self.assertEqual(len(el), 40)
        wait.until(lambda _: b.execute_script("return placed !== null"))
        w, h = frame.size["width"], frame.size["height"]

        def offset(x, y):  # picture pixels to an offset from the shown picture's centre (selenium 4)
            return x * w / 960 - w / 2, y * h / 540 - h / 2
        a, z = el[30], el[3]
        ActionChains(b).move_to_element_with_offset(frame, *offset(a[0], a[1])).click_and_hold() \
            .move_to_element_with_offset(frame, *offset(z[0], z[1])).release().perform()
        wait.until(lambda _: self.value("from") != "")
        # the stretch from element 30 forward past s = 0 to element 3 (wrapping: from > to)
        self.assertEqual((float(self.value("from")), float(self.value("to"))), (a[2], z[2]))
        self.assertGreater(a[2], z[2])
        # off the belt (the picture's top left, its text band): the form is left as it was. Before
        # Wet, whose picture of the wet belt empties the page's places while it loads (a click then
        # reads "the picture is moving") and whose reply ("queued") can come after this one's: the
        # click after Wet waited out its 60 s once in 9 runs at a load of 20
        ActionChains(b).move_to_element_with_offset(frame, *offset(4, 4)).click().perform()
        wait.until(lambda _: self.text("reply") == "no element there: pick on the belt")
        self.assertEqual((float(self.value("from")), float(self.value("to"))), (a[2], z[2]))
        b.find_element(By.ID, "mu").send_keys("0.05")
        b.find_element(By.ID, "wet").click()
        wait.until(lambda _: self.text("status").endswith(" -> 0.05)"))  # "(wet: N of 60 elements (...), mu 1 -> 0.05)"
        with open(os.path.join(self.dir, "out", "events.csv")) as f:
            wet = [r for r in f.read().splitlines() if r.split(",")[1] == "wet"]
        self.assertEqual(len(wet), 1)
        self.assertEqual(float(wet[0].split(",")[0]), T_SHOT)
        self.assertIn("mu = 0.05 on s in [%.6g, %.6g] m" % (a[2], z[2]), wet[0])

    def readme_screenshot(self, wait):
        """the README's picture of the page (--update-golden): README_COLUMNS plotted, the run taken
        on to T_README by the page's run-to control (in steps of README_STEP), the screenshot once
        the page shows that t, its picture and its plot; the run then finishes"""
        b = self.browser
        # the check boxes to change (one question to the browser: asking each box took seconds)
        flip = b.execute_script("const want = arguments[0]; return Array.from("
                                "document.querySelectorAll('#columns input')).filter(cb => cb.checked !== "
                                "want.includes(cb.dataset.column)).map(cb => cb.dataset.column);", README_COLUMNS)
        for column in flip:
            b.find_element(By.CSS_SELECTOR, "#columns input[data-column='%s']" % column).click()
        wait.until(lambda _: sorted(b.execute_script("return Array.from(document.querySelectorAll("
                                                     "'#plots .legend')).map(e => e.innerText).join(' ')").split()) ==
                   sorted(README_COLUMNS))
        q = urllib.parse.urlsplit(self.url).query
        steps = round((T_README - T_SHOT) / README_STEP)
        for k in range(1, steps):  # the page's control, as its Run button sends it
            t = round(T_SHOT + k * README_STEP, 9)
            post = urllib.request.Request(self.url.split("?")[0] + "control?" + q + "&do=run_to&value=%r" % t,
                                          data=b"", method="POST")
            self.assertEqual(urllib.request.urlopen(post, timeout=30).status, 202)
            wait.until(lambda _: self.text("status") == "paused at t = %g s" % t)
        b.find_element(By.ID, "target").send_keys(repr(T_README))  # the last with the page's own form
        b.find_element(By.ID, "runto").click()
        wait.until(lambda _: self.text("status") == "paused at t = %g s" % T_README)
        wait.until(lambda _: self.text("reply") == "")  # the control applied: no "queued" left
        frame = b.find_element(By.ID, "frame")
        wait.until(lambda _: frame.get_attribute("data-t") == repr(T_README))
        wait.until(lambda _: b.execute_script("return graphs[0].xAxisExtremes()[1]") == T_README)
        b.save_screenshot(SCREENSHOT)
        b.find_element(By.ID, "continue").click()
        self.assertEqual(self.proc.wait(timeout=RUN), 0)

    def test_watch_pause_torque_continue(self):
        b = self.browser
        # a run to T_SHOT, asked for before the run begins (the script waits for `go`): the run
        # pauses at T_SHOT exactly, the same state every time
        q = urllib.parse.urlsplit(self.url).query
        post = urllib.request.Request(self.url.split("?")[0] + "control?" + q + "&do=run_to&value=%r" % T_SHOT,
                                      data=b"", method="POST")
        self.assertEqual(urllib.request.urlopen(post, timeout=30).status, 202)
        open(self.go, "w").close()
        b.get(self.url)
        wait = WebDriverWait(b, WAIT, poll_frequency=0.05)
        wait.until(lambda _: self.text("status") == "paused at t = %g s" % T_SHOT)
        frame = b.find_element(By.ID, "frame")
        wait.until(lambda _: frame.get_attribute("data-t") == repr(T_SHOT))  # the picture of that t shown
        shot = os.path.join(self.dir, "frame.png")
        frame.screenshot(shot)
        if UPDATE:
            shutil.copy(shot, GOLDEN)
        else:
            c = subprocess.run([BELTSIM, "compare", shot, GOLDEN], capture_output=True, text=True)
            self.assertEqual(c.returncode, 0, c.stdout + c.stderr + " (the difference image: " + self.dir + ")")
        self.pick_stretch(wait)
        self.check_legend(wait)
        if UPDATE:
            self.readme_screenshot(wait)
            return
        # Continue, then Pause as soon as the page shows the run going on (status "running", t past
        # T_SHOT): pressed by the page's own script, set to watch before Continue is clicked, as the
        # page's events arrive. Watched through WebDriver instead (a round trip each look, up to a
        # second each at a load of 20), the run reached its end (in 3 s) before the Pause, and the
        # wait for the pause ran out (once in 9 runs there)
        b.execute_script("""
            const from = arguments[0], status = document.getElementById("status"), t = document.getElementById("t");
            window.seenRunning = null;
            const watch = new MutationObserver(() => {
              if (status.textContent !== "running" || !(parseFloat(t.textContent) > from)) return;
              watch.disconnect();
              window.seenRunning = parseFloat(t.textContent);
              document.getElementById("pause").click();
            });
            watch.observe(document.getElementById("bar"), { childList: true, characterData: true, subtree: true });
            """, T_SHOT)
        b.find_element(By.ID, "continue").click()
        # (paused again: the status before Continue said "paused at t = 0.05 s (wet: ...)")
        wait.until(lambda _: b.execute_script("return window.seenRunning !== null && document.getElementById("
                                              "'status').textContent.startsWith('paused at t = ')")
                   or self.proc.poll() is not None)
        self.assertIsNone(self.proc.poll(), "the run ended before the pause: " + self.text("status"))
        seen = b.execute_script("return window.seenRunning")
        self.assertGreater(seen, T_SHOT)  # t advances
        paused_at = float(self.text("status").split("= ")[1].split(" ")[0])
        self.assertGreaterEqual(paused_at, seen)
        self.assertLess(paused_at, T_END)
        Select(b.find_element(By.ID, "pulley")).select_by_visible_text("driven")
        b.find_element(By.ID, "torque").send_keys(LOAD)
        b.find_element(By.ID, "settorque").click()
        wait.until(lambda _: self.text("status").endswith("(torque applied)"))
        # the server's "queued" beside the controls is gone once the status says the torque was
        # applied (it stayed there, stale: the README's screenshot showed it after the run to t)
        wait.until(lambda _: self.text("reply") == "")
        events = os.path.join(self.dir, "out", "events.csv")

        def torque_rows():
            with open(events) as f:
                return [r.split(",") for r in f.read().splitlines()[1:] if r.split(",")[1] == "driven.torque"]
        wait.until(lambda _: torque_rows())
        b.find_element(By.ID, "continue").click()
        self.assertEqual(self.proc.wait(timeout=RUN), 0)
        rows = torque_rows()
        self.assertEqual(len(rows), 1)
        # the page's status gives t to 6 significant digits
        self.assertLessEqual(abs(float(rows[0][0]) - paused_at), 5e-6 * paused_at)
        self.assertEqual(float(rows[0][2]), float(LOAD))


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    if "--update-golden" in sys.argv:
        sys.argv.remove("--update-golden")
        UPDATE = True
    if not DRIVER:
        print("skipped: chromium-driver is not installed")
        sys.exit(77)
    unittest.main()
