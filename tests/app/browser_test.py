#!/usr/bin/env python3
"""The live view in a real browser (headless Chromium through selenium and chromium-driver, all
Debian): the page of a running dry scenario shows t advancing, Pause holds the run (the status says
where), a torque set on the page lands in events.csv at that time, Continue lets the run finish
whole. The picture of the run paused at a run-to time asked for before the run began (t = 0.05 s,
so always the same state) is compared with tests/golden/live_page_frame.png by the goldens'
metric (`beltsim compare`, media/image_compare.hpp). Each step waits for what the page shows
(WebDriverWait), no sleeps. Exit 77 (skipped) without selenium or chromium-driver.

usage: browser_test.py BELTSIM [--update-golden]
  --update-golden (the target update_browser_golden): writes the golden picture and the README's
  screenshot of the page (media/live-view.png) instead of comparing
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
import urllib.parse
import urllib.request
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

try:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.by import By
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
DRIVER = shutil.which("chromedriver")
T_END = 2.0  # [s] several seconds of wall time: the page is read mid-run
WAIT = 60  # [s] at most for what the page should show


class Browser(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_browser_")
        if not os.environ.get("BELTSIM_KEEP"):
            self.addCleanup(shutil.rmtree, self.dir, True)
        with open(os.path.join(self.dir, "s.lua"), "w") as f:
            f.write(two_pulley(elements=40) + "drive:run { t_end = %r, sample = 1e-3 }\n" % T_END)
        # the browser first: its start (seconds) is not the run's time
        o = webdriver.ChromeOptions()
        for a in ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run",
                  "--user-data-dir=" + os.path.join(self.dir, "chromium"), "--window-size=1280,1200",
                  "--force-device-scale-factor=1", "--force-color-profile=srgb"]:
            o.add_argument(a)
        self.browser = webdriver.Chrome(service=Service(DRIVER), options=o)
        self.addCleanup(self.browser.quit)
        self.proc = subprocess.Popen([BELTSIM, "run", "s.lua", "--serve", "--out", "out"], cwd=self.dir,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        self.addCleanup(self.stop)
        for line in self.proc.stderr:
            if b"live view at " in line:
                self.url = line.decode().split("live view at ")[1].strip()
                break
        else:
            self.fail("no address printed")

    def stop(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        self.proc.stderr.close()

    def text(self, id_):
        return self.browser.find_element(By.ID, id_).text

    def test_watch_pause_torque_continue(self):
        b = self.browser
        # a run to T_SHOT, asked for before the run begins (the address is printed before the
        # script runs): the run pauses at T_SHOT exactly, the same state every time
        q = urllib.parse.urlsplit(self.url).query
        post = urllib.request.Request(self.url.split("?")[0] + "control?" + q + "&do=run_to&value=%r" % T_SHOT,
                                      data=b"", method="POST")
        self.assertEqual(urllib.request.urlopen(post, timeout=30).status, 202)
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
        b.find_element(By.ID, "continue").click()
        wait.until(lambda _: self.text("status") == "running")
        t0 = float(self.text("t"))
        wait.until(lambda _: float(self.text("t")) > t0)  # t advances
        b.find_element(By.ID, "pause").click()
        wait.until(lambda _: self.text("status").startswith("paused at t = "))
        paused_at = float(self.text("status").split("= ")[1].split(" ")[0])
        self.assertLess(paused_at, T_END)
        Select(b.find_element(By.ID, "pulley")).select_by_visible_text("driven")
        b.find_element(By.ID, "torque").send_keys("-65")
        b.find_element(By.ID, "settorque").click()
        wait.until(lambda _: self.text("reply") == "queued")
        events = os.path.join(self.dir, "out", "events.csv")

        def torque_rows():
            with open(events) as f:
                return [r.split(",") for r in f.read().splitlines()[1:] if r.split(",")[1] == "driven.torque"]
        wait.until(lambda _: torque_rows())
        if UPDATE:  # the README's picture of the page
            b.save_screenshot(SCREENSHOT)
        b.find_element(By.ID, "continue").click()
        self.assertEqual(self.proc.wait(timeout=300), 0)
        rows = torque_rows()
        self.assertEqual(len(rows), 1)
        # the page's status gives t to 6 significant digits
        self.assertLessEqual(abs(float(rows[0][0]) - paused_at), 5e-6 * paused_at)
        self.assertEqual(float(rows[0][2]), -65)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    if "--update-golden" in sys.argv:
        sys.argv.remove("--update-golden")
        UPDATE = True
    if not DRIVER:
        print("skipped: chromium-driver is not installed")
        sys.exit(77)
    unittest.main()
