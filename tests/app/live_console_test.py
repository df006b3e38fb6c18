#!/usr/bin/env python3
"""A console's simulation and its live view (docs/live-view.md): `beltsim console S.lua --serve`
(and sim:serve{} at the prompt). The page's changes reach the console's simulation while a
command runs it and while the console waits at its prompt (before the first run too), and
session.lua replays them; a change after a batch run has ended or after the simulation was
closed is refused at once; each scene:run{} gets a plot of its own. The server and the page's
controls in a run: live_test.py.

usage: live_console_test.py BELTSIM
"""
import http.client
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.parse
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402
from live_page import LOAD, SAMPLE, Page, events, events_csv, status_t  # noqa: E402

BELTSIM = None


class ConsoleAndPage(unittest.TestCase):
    """a console's simulation changed from the page while a command runs it: the page's changes are
    applied on the console's thread between two run_to calls, before the console's next command
    (never interleaved), and session.lua replays them where they came: the replay's events.csv and
    timeseries.csv are the session's, byte for byte"""

    def console(self, prefix, stdout, serve=True):
        """a console on the two-pulley drive's simulation (sim) with --serve (unless not serve), in a
        folder of its own"""
        d = tempfile.mkdtemp(prefix=prefix)
        self.addCleanup(shutil.rmtree, d, True)
        with open(os.path.join(d, "c.lua"), "w") as f:
            f.write(two_pulley(elements=40) + "sim = drive:start { out = \"out\", sample = %r }\n" % SAMPLE)
        proc = subprocess.Popen([BELTSIM, "console", "c.lua"] + (["--serve"] if serve else []), cwd=d,
                                stdin=subprocess.PIPE, stdout=stdout, stderr=subprocess.PIPE)
        self.addCleanup(proc.kill)
        return d, proc

    def page(self, proc):
        """the console's page: a Live on its address, the stream's connection and its statuses"""
        for line in proc.stderr:
            if b"live view at " in line:
                url = urllib.parse.urlsplit(line.decode().split("live view at ")[1].strip())
                break
        live = Page()
        live.url, live.token = url, urllib.parse.parse_qs(url.query)["token"][0]
        c = http.client.HTTPConnection(url.hostname, url.port, timeout=60)
        c.request("GET", "/events?token=" + live.token)
        return live, c, live.statuses(c.getresponse())

    def paused_mid_run(self, prefix, stdout, commands):
        """a console given `commands` (its input then closed), its page, and the run the commands
        start paused from the page once it has a sample: (folder, process, page, connection,
        statuses, the status "paused at t = ... s")"""
        d, proc = self.console(prefix, stdout)
        proc.stdin.write(commands)
        proc.stdin.close()
        live, c, it = self.page(proc)
        for _ in it:
            if live.t:
                break
        self.assertEqual(live.post("do=pause")[0], 202)
        return d, proc, live, c, it, live.wait_status(it, "paused at t = ")

    def replay(self, d, session):
        """session (relative to d) run alone in d/replay, which it returns"""
        r = os.path.join(d, "replay")
        os.mkdir(r)
        shutil.copy(os.path.join(d, session), os.path.join(r, "session.lua"))
        p = subprocess.run([BELTSIM, "run", "session.lua"], cwd=r, capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.replay_stdout = p.stdout
        return r

    def test_page_changes_in_events_and_session(self):
        # the console's commands are waiting on its input before the page does anything
        d, proc, live, c, it, paused = self.paused_mid_run("beltsim_live_console_", subprocess.DEVNULL,
                                                           b"sim:run_to(0.6)\nsim:set_torque('driven', -30)\n")
        paused_at = float(paused.split("= ")[1].split(" ")[0])
        self.assertEqual(live.post("do=torque&pulley=driven&value=%r" % LOAD)[0], 202)
        self.assertEqual(live.post("do=wet&from=0.1&to=0.3&value=0.05")[0], 202)
        # the status says what the wet did, as sim:wet says it at the prompt
        status = live.wait_status(it, "paused at t = %s s (wet: " % status_t(paused_at))
        self.assertRegex(status, r"\(wet: \d+ of \d+ elements \(.+\), mu [0-9.]+ -> 0\.05\)$")
        # the same wet again changes nothing: said so, and not recorded (events.csv below: one wet)
        self.assertEqual(live.post("do=wet&from=0.1&to=0.3&value=0.05")[0], 202)
        live.wait_status(it, "paused at t = %s s (wet: no element changed (the " % status_t(paused_at))
        self.assertEqual(live.post("do=continue")[0], 202)
        c.close()
        err = proc.stderr.read().decode()
        self.assertEqual(proc.wait(timeout=300), 0, err)
        rows = events_csv(os.path.join(d, "out"))
        changes = [(row[1], row[2]) for row in rows if row[1] in ("driven.torque", "wet")]
        self.assertEqual([c[0] for c in changes], ["driven.torque", "wet", "driven.torque"], rows)
        self.assertEqual([float(c[1]) for c in changes if c[0] == "driven.torque"], [LOAD, -30])
        t = [float(row[0]) for row in rows if row[1] in ("driven.torque", "wet")]
        self.assertLessEqual(abs(t[0] - paused_at), 5e-6 * paused_at)
        self.assertEqual((t[1], t[2]), (t[0], 0.6))
        session = err.split("the session's commands are in ")[1].split("\n")[0]
        with open(os.path.join(d, session)) as f:
            text = f.read()
        at = [text.index("\n" + s + "\n") for s in [
            "sim:run_to(%r)" % t[0], 'sim:set_torque("driven", %r)' % LOAD, "sim:wet { from = 0.1, to = 0.3, mu = 0.05 }",
            "sim:run_to(0.6)", "sim:set_torque('driven', -30)"]]
        self.assertEqual(at, sorted(at), text)
        # the replay: the same outputs
        r = self.replay(d, session)
        with open(os.path.join(d, "out", "events.csv")) as a, open(os.path.join(r, "out", "events.csv")) as b:
            self.assertEqual(a.read(), b.read())
        # every sample, the interval means of the sample interval that holds the page's change too
        with open(os.path.join(d, "out", "timeseries.csv")) as a, open(os.path.join(r, "out", "timeseries.csv")) as b:
            a, b = a.read().splitlines(), b.read().splitlines()
        self.assertEqual(len(a), len(b))
        head = a[0].split(",")
        for x, y in zip(a, b):
            x, y = x.split(","), y.split(",")
            self.assertEqual([(h, u) for h, u, v in zip(head, x, y) if u != v],
                             [(h, v) for h, u, v in zip(head, x, y) if u != v], x[0])

    def test_a_page_run_to_past_the_consoles_run_to_says_where_it_stopped(self):
        """the page asks for a run to 2 s while the console's sim:run_to(1) runs: the run ends at
        1 s, and the status says the page's run to lies past it (it said "paused" alone, a user's
        trial); the console's next run_to does not stop at the page's stale 2 s"""
        d, proc = self.console("beltsim_live_past_", subprocess.PIPE)
        # the next commands only once the status is seen: a command that starts a run at once
        # replaces the status before a slow stream reads it
        proc.stdin.write(b"sim:run_to(1)\n")
        proc.stdin.flush()
        live, c, it = self.page(proc)
        for _ in it:
            if live.t:
                break
        self.assertEqual(live.post("do=pause")[0], 202)
        live.wait_status(it, "paused at t = ", within=60)
        self.assertEqual(live.post("do=run_to&value=2")[0], 202)
        live.wait_status(it, "paused at t = 1 s: the page's run to 2 s lies past the end of this run_to", within=60)
        proc.stdin.write(b"print('at', sim.t)\nsim:run_to(2.5)\nprint('then', sim.t)\n")
        proc.stdin.close()
        out = proc.stdout.read().decode()
        self.assertEqual(proc.wait(timeout=300), 0)
        self.assertIn("at\t1.0\n", out)
        self.assertIn("then\t2.5\n", out)
        c.close()

    def test_an_assignment_changed_from_the_page_replays(self):
        """`r = sim:run_to(T)` changed from the page while it ran, and a command reading r after it:
        session.lua keeps the assignment on the run's last part (`r = sim:run_to(T)`), so that the
        replay exits 0, prints what the console printed and gives its time series byte for byte. It
        was replayed without `r =`: "attempt to index a nil value (global 'r')", exit 1"""
        d, proc, live, c, it, paused_at = self.paused_mid_run("beltsim_live_kept_", subprocess.PIPE,
                                                              b"r = sim:run_to(0.6)\nprint('r', r.t, r.interrupted)\n")
        self.assertEqual(live.post("do=torque&pulley=driven&value=%r" % LOAD)[0], 202)
        live.wait_status(it, paused_at + " (torque applied)")
        self.assertEqual(live.post("do=continue")[0], 202)
        c.close()
        out = proc.stdout.read().decode()
        err = proc.stderr.read().decode()
        self.assertEqual(proc.wait(timeout=300), 0, err)
        self.assertIn("r\t0.6\tfalse\n", out)
        session = err.split("the session's commands are in ")[1].split("\n")[0]
        with open(os.path.join(d, session)) as f:
            lines = f.read().splitlines()
        at = lines.index("-- r = sim:run_to(0.6)  -- changed from the live view while it ran")
        self.assertEqual([lines[at + 2], lines[at + 3]], ['sim:set_torque("driven", %r)' % LOAD, "r = sim:run_to(0.6)"])
        r = self.replay(d, session)
        self.assertIn("r\t0.6\tfalse\n", self.replay_stdout)
        for name in ["events.csv", "timeseries.csv"]:
            with open(os.path.join(d, "out", name)) as a, open(os.path.join(r, "out", name)) as b:
                self.assertEqual(a.read(), b.read(), name)

    def test_a_change_at_the_prompt_applies_there(self):
        """a torque sent from the page while the console waits at its prompt after sim:run_to(T)
        is applied there, at T (no run needed): the status says so, the console's next
        inspection reads it, events.csv has it at T, session.lua has it before the next run and
        its replay gives the same events.csv and timeseries.csv"""
        d, proc = self.console("beltsim_live_prompt_", subprocess.PIPE)
        live, c, it = self.page(proc)
        t_pause = 0.05
        proc.stdin.write(b"sim:run_to(%r)\n" % t_pause)
        proc.stdin.flush()
        # sim:run_to has returned: the console is at its prompt (the page said "paused" at t = 0
        # already, where the console waited before it)
        self.page_at_the_prompt(live, it, t_pause)
        # applied at the prompt, not after the first step of the console's next run (before the
        # fix nothing came until the console ran again)
        err = self.change_at_the_prompt(d, proc, live, it, t_pause, then=b"sim:run_to(0.1)\n", stream=c)
        session = err.split("the session's commands are in ")[1].split("\n")[0]
        with open(os.path.join(d, session)) as f:
            text = f.read()
        at = [text.index("\n" + s) for s in [
            "sim:run_to(%r)" % t_pause, 'sim:set_torque("driven", -65)', "print('torque'", "sim:run_to(0.1)"]]
        self.assertEqual(at, sorted(at), text)
        r = self.replay(d, session)
        for name in ["events.csv", "timeseries.csv"]:
            with open(os.path.join(d, "out", name)) as a, open(os.path.join(r, "out", name)) as b:
                self.assertEqual(a.read(), b.read(), name)

    def page_at_the_prompt(self, live, it, t):
        """the page of a simulation at the console's prompt at t: its run (its pulleys), the
        sample of t, the status "paused", and the picture of t (a JPEG; /frame.jpg answered 503
        "no frame yet" there)"""
        end = time.monotonic() + 60  # a bound on a failure: the frame thread's start takes 0.1 s
        for _ in it:
            if live.t == t and live.frames and live.frames[-1] == t and live.status == "paused":
                break
            self.assertLess(time.monotonic(), end, (live.run, live.t, live.frames, live.status))
        self.assertEqual(live.run["pulleys"], ["driver", "driven"])
        self.assertIn("driver.omega", live.run["columns"])
        status, frame = live.get("/frame.jpg?token=" + live.token)
        self.assertEqual((status, frame[:2]), (200, b"\xff\xd8"))

    def change_at_the_prompt(self, d, proc, live, it, t, then=b"", stream=None):
        """a torque sent from the page at the prompt: applied there (the status, the console's next
        print, events.csv at t); `then`: the console's commands after the print; `stream`: the
        page's stream, closed before them"""
        self.assertEqual(live.post("do=torque&pulley=driven&value=-65"), (202, "queued\n"))
        live.wait_status(it, "paused at t = %s s (torque applied)" % status_t(t), within=30)
        if stream:
            stream.close()
        proc.stdin.write(b"print('torque', sim:pulley('driven').torque)\n" + then)
        proc.stdin.close()
        out = proc.stdout.read().decode()
        err = proc.stderr.read().decode()
        self.assertEqual(proc.wait(timeout=300), 0, err)
        self.assertIn("torque\t-65", out)
        # the console says it as it says its own changes (a trial saw it only as a warning on the prompt)
        self.assertIn("beltsim: live view: torque applied at t = %s s\n" % status_t(t), err)
        rows = [r for r in events_csv(os.path.join(d, "out")) if r[1] == "driven.torque"]
        self.assertEqual([(float(r[0]), float(r[2])) for r in rows], [(t, -65)])
        return err

    def test_a_page_before_the_first_run(self):
        """console S.lua --serve, S.lua starts sim and nothing has run: the page shows sim at t = 0
        (its pulleys, its sample, its picture) and a change from the page is applied to it at the
        prompt (it was refused: 'no simulation to change (the run has ended)'), recorded in
        session.lua"""
        d, proc = self.console("beltsim_live_first_", subprocess.PIPE)
        live, c, it = self.page(proc)
        self.page_at_the_prompt(live, it, 0)
        err = self.change_at_the_prompt(d, proc, live, it, 0)
        session = err.split("the session's commands are in ")[1].split("\n")[0]
        with open(os.path.join(d, session)) as f:
            self.assertIn('\nsim:set_torque("driven", -65)  -- from the live view\n', f.read())
        c.close()

    def test_a_change_after_a_batch_run_is_refused_at_once(self):
        """console S.lua --serve, S.lua's scene:run{} has ended: a change from the page is refused
        at once (409, naming why; it was answered "queued" and refused later in the status), until
        a run begins again: then it is queued and applied at the prompt"""
        d = tempfile.mkdtemp(prefix="beltsim_live_ended_")
        self.addCleanup(shutil.rmtree, d, True)
        with open(os.path.join(d, "c.lua"), "w") as f:
            f.write(two_pulley(elements=40) + "drive:run { t_end = 0.002, out = 'first', progress = false }\n"
                    "the_drive = drive\n")
        proc = subprocess.Popen([BELTSIM, "console", "c.lua", "--serve"], cwd=d, stdin=subprocess.PIPE,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.addCleanup(proc.kill)
        live, c, it = self.page(proc)
        proc.stdin.write(b"print('ready')\n")  # the console is at its prompt: the run has ended
        proc.stdin.flush()
        self.assertEqual(proc.stdout.readline(), b"ready\n")
        for query in ["do=torque&pulley=driven&value=-65", "do=pause", "do=save&name=x.ckpt"]:
            self.assertEqual(live.post(query), (409, "refused: %s: no simulation to change (the run has ended)\n" %
                                                 query.split("&")[0][3:]))
        self.assertEqual(live.post("do=torque&pulley=driven&value=x")[0], 400)  # a bad one says what is wrong
        t = 0.002
        proc.stdin.write(b"sim = the_drive:start { out = 'out', progress = false }\nsim:run_to(%r)\n" % t)
        proc.stdin.flush()
        self.page_at_the_prompt(live, it, t)
        self.change_at_the_prompt(d, proc, live, it, t)
        c.close()

    def test_a_refusal_in_the_consoles_words(self):
        """the page's refusal of a mistake says what the console says of the same one: a pulley that
        does not exist (400 at once; it was "queued", then "refused: no pulley 'drivn'") and a μ out
        of range (the status; it lacked "(got -1 for element N)")"""
        d, proc = self.console("beltsim_live_words_", subprocess.PIPE)
        live, c, it = self.page(proc)
        self.page_at_the_prompt(live, it, 0)
        status, torque = live.post("do=torque&pulley=drivn&value=-40")
        self.assertEqual(status, 400, torque)
        self.assertEqual(live.post("do=wet&from=0.1&to=0.3&value=-1"), (202, "queued\n"))
        wet = live.wait_status(it, "refused: ", within=30)
        c.close()
        proc.stdin.write(b"print(select(2, pcall(sim.set_torque, sim, 'drivn', -40)))\n"
                         b"print(select(2, pcall(sim.wet, sim, { from = 0.1, to = 0.3, mu = -1 })))\n")
        proc.stdin.close()
        out = proc.stdout.read().decode().splitlines()
        self.assertEqual(proc.wait(timeout=120), 0, proc.stderr.read().decode())
        self.assertEqual(out[-2], "sim:set_torque: no pulley 'drivn' (did you mean 'driven'?); pulleys: driver, driven")
        self.assertEqual(torque, "torque: " + out[-2][len("sim:set_torque: "):] + "\n")
        self.assertRegex(out[-1], r"^sim:wet\.mu: .* \(got -1 for element \d+\)$")
        self.assertEqual(wet, "refused: wet.mu: " + out[-1][len("sim:wet.mu: "):])

    def test_each_run_a_plot_of_its_own(self):
        """two scene:run{} in a row, the second with columns of its own (two probes): the page gets
        a run of each, the second's name and columns and its samples alone (from t = 0). The page
        keyed a run by the simulation's address, and run(){}'s simulation lives on the stack: the
        second had the first's address, and the page kept the first's name, columns and plot"""
        d = tempfile.mkdtemp(prefix="beltsim_live_runs_")
        self.addCleanup(shutil.rmtree, d, True)
        with open(os.path.join(d, "c.lua"), "w") as f:
            f.write(two_pulley(elements=40) + "the_drive = drive\n")
        proc = subprocess.Popen([BELTSIM, "console", "c.lua", "--serve"], cwd=d, stdin=subprocess.PIPE,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        self.addCleanup(proc.kill)
        live, c, _ = self.page(proc)
        c.close()  # the page's events as they come, not its statuses alone
        c = http.client.HTTPConnection(live.url.hostname, live.url.port, timeout=60)
        c.request("GET", "/events?token=" + live.token)
        stream = events(c.getresponse())
        runs = []
        for command, name, t_end in [(b"the_drive:run { t_end = 0.002, out = 'first', progress = false }\n",
                                      "first", 0.002),
                                     (b"the_drive:run { t_end = 0.003, out = 'second', probe = { 12, 30 }, "
                                      b"progress = false }\n", "second", 0.003)]:
            proc.stdin.write(command)
            proc.stdin.flush()
            end = time.monotonic() + 60  # a bound on a failure: the run event never came
            samples = None  # this run's, from its run event on
            for name_, data in stream:
                if name_ == "run":
                    samples = [] if json.loads(data)["name"] == name else None
                    runs.append(json.loads(data))
                elif name_ == "samples" and samples is not None:
                    samples += [row[0] for row in json.loads(data)]
                elif name_ == "status" and json.loads(data) == "finished" and samples:
                    break
                self.assertLess(time.monotonic(), end, (name, [r["name"] for r in runs]))
            self.assertEqual(runs[-1]["name"], name)
            self.assertEqual(samples[0], 0, name)  # its own samples only, from t = 0 to its end
            self.assertEqual(samples, sorted(samples), name)
            self.assertAlmostEqual(samples[-1], t_end, places=12)
        first, second = runs[-2], runs[-1]
        self.assertEqual(first["name"], "first")
        self.assertIn("probe.normal_force", first["columns"])
        self.assertNotIn("probe1.normal_force", first["columns"])
        self.assertEqual([k for k in ("probe.normal_force", "probe1.normal_force", "probe2.normal_force")
                          if k in second["columns"]], ["probe1.normal_force", "probe2.normal_force"])
        proc.stdin.close()
        self.assertEqual(proc.wait(timeout=120), 0)
        c.close()

    def test_a_change_after_close_is_refused_at_once(self):
        """the simulation the page shows closed at the prompt (sim:close(), or finalised by the
        collector): the page's status says so and a change is refused at once (409) and reaches
        no simulation. After sim:close() the console's prompt went on feeding the closed
        simulation to the page: "queued", then its sample, its picture and "refused: set_torque:
        the simulation is closed" """
        for ending, why in [(b"sim:close()", "closed"), (b"sim = nil; collectgarbage()", "finalised")]:
            d, proc = self.console("beltsim_live_closed_", subprocess.PIPE)
            live, c, it = self.page(proc)
            proc.stdin.write(b"sim:run_to(0.01)\n" + ending + b"\nprint('ready')\n")
            proc.stdin.flush()
            for line in proc.stdout:
                if line == b"ready\n":
                    break
            live.wait_status(it, "%s at t = 0.01 s" % why, within=30)
            for query in ["do=torque&pulley=driven&value=-65", "do=save&name=x.ckpt", "do=pause"]:
                self.assertEqual(live.post(query), (409, "refused: %s: no simulation to change (it is %s)\n" %
                                                     (query.split("&")[0][3:], why)), ending)
            c.close()
            proc.stdin.close()
            proc.stdout.read()
            self.assertEqual(proc.wait(timeout=120), 0, proc.stderr.read().decode())
            proc.stderr.close()
            self.assertEqual([r for r in events_csv(os.path.join(d, "out")) if r[1] == "driven.torque"], [], ending)
            self.assertFalse(os.path.exists(os.path.join(d, "out", "x.ckpt")), ending)

    def test_sim_serve_at_the_prompt(self):
        """sim:serve{} typed at the prompt, then sim:run_to(T): a torque from its page is applied
        at the prompt at T (it stayed queued until the next run_to)"""
        d, proc = self.console("beltsim_live_served_", subprocess.PIPE, serve=False)
        t = 0.05
        proc.stdin.write(b"sim:serve{}\n")
        proc.stdin.flush()
        live, c, it = self.page(proc)
        self.page_at_the_prompt(live, it, 0)
        proc.stdin.write(b"sim:run_to(%r)\n" % t)
        proc.stdin.flush()
        self.page_at_the_prompt(live, it, t)
        self.change_at_the_prompt(d, proc, live, it, t)
        c.close()



if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
