#!/usr/bin/env python3
"""The live view's server (docs/live-view.md, src/live/): `beltsim run S.lua --serve` answers 403
without the token printed at its start, serves the page and its plotting library with it and
nothing else, streams samples whose t advances and the renderer's frames (PNG) while a page is
open, and a client that disconnects mid-run leaves the
run to finish whole (timeseries.csv to t_end, exit 0). Each step waits for what it needs (the
address on stderr, the stream's events); no sleeps.

usage: live_test.py BELTSIM
"""
import http.client
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import unittest
import urllib.parse
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None
T_END = 1.0  # [s] long enough (several seconds of wall time) for the stream to be read mid-run
SAMPLE = 1e-3  # [s] the runs' sample interval: timeseries.csv has T_END / SAMPLE + 1 rows


def events(resp):
    """the stream's events as (name, data) pairs, as they arrive"""
    name, data = "message", []
    while True:
        line = resp.readline()
        if not line:
            return
        line = line.decode().rstrip("\n")
        if line == "":
            if data:
                yield name, "\n".join(data)
            name, data = "message", []
        elif line.startswith("event: "):
            name = line[7:]
        elif line.startswith("data: "):
            data.append(line[6:])


class Live(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_live_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        with open(os.path.join(self.dir, "s.lua"), "w") as f:
            f.write(two_pulley(elements=40) + "drive:run { t_end = %r, sample = %r }\n" % (T_END, SAMPLE))
        self.proc = subprocess.Popen([BELTSIM, "run", "s.lua", "--serve", "--out", "out"], cwd=self.dir,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        self.addCleanup(self.stop)
        self.stderr = []
        for line in self.proc.stderr:
            line = line.decode()
            self.stderr.append(line)
            if "live view at " in line:
                self.url = urllib.parse.urlsplit(line.split("live view at ")[1].strip())
                break
        else:
            self.fail("no address printed: " + "".join(self.stderr))
        self.token = urllib.parse.parse_qs(self.url.query)["token"][0]

    def stop(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        self.proc.stderr.close()

    def get(self, path):
        c = http.client.HTTPConnection(self.url.hostname, self.url.port, timeout=30)
        c.request("GET", path)
        r = c.getresponse()
        body = r.read()
        c.close()
        return r.status, body

    def post(self, query):
        c = http.client.HTTPConnection(self.url.hostname, self.url.port, timeout=30)
        c.request("POST", "/control?token=" + self.token + "&" + query, body=b"")
        r = c.getresponse()
        body = r.read()
        c.close()
        return r.status, body.decode()

    def test_controls_pause_torque_continue(self):
        """the page's controls reach the run between two steps: pause holds it (the stream's status
        says where), a torque lands in events.csv at that time, continue lets it finish whole"""
        self.assertEqual(self.post("do=pause")[0], 202)
        c = http.client.HTTPConnection(self.url.hostname, self.url.port, timeout=60)
        c.request("GET", "/events?token=" + self.token)
        r = c.getresponse()
        paused_at, statuses = None, []
        for name, data in events(r):
            if name != "status":
                continue
            status = json.loads(data)
            statuses.append(status)
            if status.startswith("paused at t = ") and paused_at is None:
                paused_at = float(status.split("= ")[1].split(" ")[0])
                self.assertEqual(self.post("do=torque&pulley=nope&value=1"), (202, "queued\n"))
                self.assertEqual(self.post("do=torque&pulley=driven&value=-65")[0], 202)
            elif status.startswith("refused: no pulley 'nope'"):
                pass
            elif status.startswith("paused at") and "refused: no pulley 'nope'" in statuses:
                break  # the torque applied while paused
        self.assertEqual(self.post("do=jump")[0], 400)
        self.assertEqual(self.post("do=torque&pulley=driven&value=x")[0], 400)
        self.assertEqual(self.post("do=continue")[0], 202)
        c.close()
        self.assertEqual(self.proc.wait(timeout=300), 0, self.proc.stderr.read().decode())
        with open(os.path.join(self.dir, "out", "events.csv")) as f:
            rows = [line.split(",") for line in f.read().splitlines()[1:]]
        torque = [row for row in rows if row[1] == "driven.torque"]
        self.assertEqual(len(torque), 1, rows)
        # where the page said it was paused (its status gives t to 6 significant digits)
        self.assertLessEqual(abs(float(torque[0][0]) - paused_at), 5e-6 * paused_at)
        self.assertEqual(float(torque[0][2]), -65)
        with open(os.path.join(self.dir, "out", "timeseries.csv")) as f:
            self.assertEqual(len(f.read().splitlines()), 1 + round(T_END / SAMPLE) + 1)

    def test_token_page_stream_and_a_client_that_leaves(self):
        self.assertEqual(self.url.hostname, "127.0.0.1")  # bound to loopback unless host is given
        for path in ["/", "/events", "/dygraph.js", "/?token=" + self.token[:-1], "/?token="]:
            self.assertEqual(self.get(path)[0], 403, path)
        q = "?token=" + self.token
        status, page = self.get("/" + q)
        self.assertEqual(status, 200)
        self.assertIn(b"dygraph.js" + q.encode(), page)
        self.assertEqual(self.get("/dygraph.js" + q)[0], 200)
        self.assertIn(b"Dygraph", self.get("/dygraph.js" + q)[1])
        for path in ["/%2e%2e/%2e%2e/etc/passwd", "/dygraph.min.js", "/index.js", "/src/dygraph.js"]:
            self.assertEqual(self.get(path + q)[0], 404, path)

        c = http.client.HTTPConnection(self.url.hostname, self.url.port, timeout=60)
        c.request("GET", "/events" + q)
        r = c.getresponse()
        self.assertEqual(r.status, 200)
        self.assertEqual(r.getheader("Content-Type"), "text/event-stream")
        columns, times, frame = None, [], None
        for name, data in events(r):
            if name == "run":
                columns = json.loads(data)["columns"]
            elif name == "samples":
                for row in json.loads(data):
                    self.assertEqual(len(row), 3 + len(columns))  # t, wall/simulated, step, the columns
                    times.append(row[0])
                # the renderer's latest frame, drawn on its own thread while a page is open (503
                # until the first is drawn)
                status, body = self.get("/frame.png" + q)
                if status == 200:
                    frame = body
                else:
                    self.assertEqual(status, 503)
            if len(times) >= 5 and times[-1] > times[0] and frame:
                break
        self.assertIn("driver.omega", columns)
        # a frame may not be drawn yet on a busy machine before the run ends (the first takes the
        # GL context's start): checked when one came (a known gap: docs/live-view.md)
        if frame is not None:
            self.assertEqual(frame[:8], b"\x89PNG\r\n\x1a\n")
            self.assertEqual(struct.unpack(">II", frame[16:24]), (960, 540))  # IHDR: width, height
        self.assertEqual(times, sorted(times))
        self.assertLess(times[-1], T_END)  # read mid-run
        c.close()  # the client leaves mid-run

        self.assertEqual(self.proc.wait(timeout=300), 0, "".join(self.stderr) + self.proc.stderr.read().decode())
        with open(os.path.join(self.dir, "out", "timeseries.csv")) as f:
            rows = f.read().splitlines()
        self.assertEqual(len(rows), 1 + round(T_END / SAMPLE) + 1)  # the header, t = 0 .. T_END
        self.assertAlmostEqual(float(rows[-1].split(",")[0]), T_END, places=12)


class ServeOption(unittest.TestCase):
    """--serve takes a port only when a number follows it (or with =): `run --serve S.lua` serves
    on a free port and runs S.lua, it does not read S.lua as the port"""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_serve_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        with open(os.path.join(self.dir, "s.lua"), "w") as f:
            f.write(two_pulley(elements=20) + "drive:run { t_end = 0.01, progress = false }\n")

    def served_port(self, args):
        p = subprocess.run([BELTSIM] + args, cwd=self.dir, input="", capture_output=True, text=True, timeout=120)
        self.assertEqual(p.returncode, 0, " ".join(args) + ": " + p.stderr)
        self.assertIn("live view at http://127.0.0.1:", p.stderr)
        return urllib.parse.urlsplit(p.stderr.split("live view at ")[1].split()[0]).port

    def free_port(self):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            return s.getsockname()[1]

    def test_a_port_only_when_a_number_follows(self):
        for args in [["run", "--serve", "s.lua"], ["run", "s.lua", "--serve"],
                     ["run", "--serve", "s.lua", "--out", "o"], ["console", "--serve", "s.lua"]]:
            self.assertGreater(self.served_port(args), 0)
        port = self.free_port()
        self.assertEqual(self.served_port(["run", "s.lua", "--serve", str(port)]), port)
        port = self.free_port()
        self.assertEqual(self.served_port(["run", "--serve=%d" % port, "s.lua"]), port)
        port = self.free_port()
        self.assertEqual(self.served_port(["run", "--serve", str(port), "s.lua"]), port)
        p = subprocess.run([BELTSIM, "run", "s.lua", "--serve=x"], cwd=self.dir, capture_output=True, text=True)
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertIn("--serve", p.stderr)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
