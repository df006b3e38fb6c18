#!/usr/bin/env python3
"""The live view's server (docs/live-view.md, src/live/): `beltsim run S.lua --serve` answers 403
without the token printed at its start, serves the page and its plotting library with it and
nothing else, streams samples whose t advances and the renderer's frames (JPEG) while a page is
open, and a client that disconnects mid-run leaves the run to finish whole (timeseries.csv to
t_end, exit 0); the page's controls reach the run; --serve takes a port only when a number follows
it, and a port in use is refused. A console's simulation and its page: live_console_test.py. Each
step waits for what it needs (the address on stderr, the stream's events); no sleeps.

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
from live_page import LOAD, LOAD_AT_TARGET, SAMPLE, Page, events, events_csv, status_t  # noqa: E402

BELTSIM = None
T_END = 1.0  # [s] long enough (several seconds of wall time) for the stream to be read mid-run
# (timeseries.csv has T_END / SAMPLE + 1 rows)


class Live(unittest.TestCase, Page):
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

    def assert_run_whole(self):
        """the run ends with exit 0 and every sample of timeseries.csv written"""
        self.assertEqual(self.proc.wait(timeout=300), 0, "".join(self.stderr) + self.proc.stderr.read().decode())
        with open(os.path.join(self.dir, "out", "timeseries.csv")) as f:
            rows = f.read().splitlines()
        self.assertEqual(len(rows), 1 + round(T_END / SAMPLE) + 1)  # the header, t = 0 .. T_END
        self.assertAlmostEqual(float(rows[-1].split(",")[0]), T_END, places=12)

    def post_without_body(self, query, headers=b""):
        """a POST with no body and, unless headers give one, no Content-Length (curl -X POST URL):
        the status and the answer"""
        with socket.create_connection((self.url.hostname, self.url.port), timeout=30) as s:
            s.sendall(b"POST /control?token=%s&%s HTTP/1.1\r\nHost: x\r\nConnection: close\r\n%s\r\n" %
                      (self.token.encode(), query.encode(), headers))
            answer = b""
            while True:
                got = s.recv(4096)
                if not got:
                    break
                answer += got
        head, _, body = answer.partition(b"\r\n\r\n")
        return int(head.split()[1]), body.decode()


    def test_controls_pause_frame_torque_wet_save_run_to(self):
        """the page's controls reach the run between two run_to calls on the thread that runs it:
        pause holds it (the stream's status says where, and a frame of that t comes), a torque, a
        wet stretch and a checkpoint land in events.csv at that time, a run to t pauses exactly
        there, continue lets it finish whole"""
        c = http.client.HTTPConnection(self.url.hostname, self.url.port, timeout=60)
        c.request("GET", "/events?token=" + self.token)
        it = self.statuses(c.getresponse())
        for _ in it:  # the run under way
            if self.t:
                break
        # as docs/live-view.md's example is sent (curl -X POST, no body): it was a bare 400
        self.assertEqual(self.post_without_body("do=pause"), (202, "queued\n"))
        status = self.wait_status(it, "paused at t = ")
        paused_at = float(status.split("= ")[1].split(" ")[0])
        # the picture of the paused run: a frame event with its t (the renderer's thread draws the
        # state offered at the pause), then /frame.jpg and where its elements are (/frame.json); no
        # timing involved
        self.assertGreater(paused_at, 0)
        for _ in it:
            if self.frames and abs(self.frames[-1] - paused_at) <= 5e-6 * paused_at:
                break
        status, frame = self.get("/frame.jpg?token=" + self.token)
        self.assertEqual(status, 200)
        self.assertEqual(frame[:2], b"\xff\xd8")  # a JPEG's start of image
        sof = frame.index(b"\xff\xc0")  # baseline start of frame: precision, height, width
        self.assertEqual(struct.unpack(">HH", frame[sof + 5:sof + 9]), (540, 960))
        status, placed = self.get("/frame.json?token=" + self.token)
        placed = json.loads(placed)
        self.assertEqual(placed["t"], self.frames[-1])
        self.assertEqual(len(placed["elements"]), 40)
        for x, y, s in placed["elements"]:  # in the picture, each at its belt coordinate
            self.assertTrue(0 <= x < 960 and 0 <= y < 540 and 0 <= s < placed["length"], (x, y, s))
        self.assertEqual(sorted(e[2] for e in placed["elements"])[0], 0)  # element 0 at s = 0

        # a pulley the run has not: refused at once, in the console's words (it was "queued", then
        # the status "refused: no pulley 'drivn'"); live_console_test.py compares them
        self.assertEqual(self.post("do=torque&pulley=drivn&value=1"),
                         (400, "torque: no pulley 'drivn' (did you mean 'driven'?); pulleys: driver, driven\n"))
        self.assertEqual(self.post("do=torque&pulley=driven&value=%r" % LOAD)[0], 202)
        self.wait_status(it, "paused at t = %s s (torque applied)" % status_t(paused_at))
        self.assertEqual(self.post("do=wet&from=0.1&to=99&value=0.05")[0], 202)
        self.assertIn("wet.to: must be in [0, ", self.wait_status(it, "refused: "))
        self.assertEqual(self.post("do=wet&from=0.1&to=0.3&value=-1")[0], 202)  # with the value, as the console
        self.assertRegex(self.wait_status(it, "refused: "), r"^refused: wet\.mu: must be in \[0, 10\]: .* \(got -1 for "
                                                          r"element \d+\)$")
        self.assertEqual(self.post("do=wet&from=0.1&to=0.3&value=0.05")[0], 202)
        self.assertRegex(self.wait_status(it, "paused at t = %s s (wet: " % status_t(paused_at)), r" -> 0\.05\)$")
        self.assertEqual(self.post("do=save&name=live.ckpt")[0], 202)
        self.wait_status(it, "paused at t = %s s (save applied)" % status_t(paused_at))
        target = round(paused_at + 0.1, 3)
        self.assertEqual(self.post("do=run_to&value=%r" % target)[0], 202)
        self.wait_status(it, "paused at t = %s s" % status_t(target))
        self.assertEqual(self.post("do=torque&pulley=driven&value=%r" % LOAD_AT_TARGET)[0], 202)  # where it paused
        self.wait_status(it, "paused at t = %s s (torque applied)" % status_t(target))
        # a run to a time not after now says where now is (it said "not after now" alone)
        self.assertEqual(self.post("do=run_to&value=%r" % (target - 0.05))[0], 202)
        self.assertEqual(self.wait_status(it, "refused: "), "refused: run to %s s: not after now, t = %s s" %
                         (status_t(target - 0.05), status_t(target)))
        for bad in ["do=jump", "do=torque&pulley=driven&value=x", "do=wet&from=0.1&value=0.2",
                    "do=save&name=../x.ckpt", "do=save&name=.x", "do=run_to&value=inf"]:
            self.assertEqual(self.post(bad)[0], 400, bad)
        # decimal numbers only (strtod read 0x10 as 16), refused naming the value
        for bad in ["do=torque&pulley=driven&value=0x10", "do=run_to&value=0x1p-1", "do=wet&from=0X0&to=0.1&value=0.2",
                    "do=torque&pulley=driven&value=%205", "do=torque&pulley=driven&value=nan"]:
            status, said = self.post(bad)
            self.assertEqual(status, 400, bad)
            self.assertIn("decimal", said, bad)
        status, said = self.post("do=torque&pulley=driven&value=0x10")
        self.assertIn("value='0x10'", said)
        # a body announced and never sent: cpp-httplib's own 400 (after its read timeout, 5 s;
        # the run is paused), which had an empty body
        status, said = self.post_without_body("do=jump", b"Content-Length: 3\r\n")
        self.assertEqual((status, said.split(" (")[0]), (400, "400: the request could not be read"))
        self.assertEqual(self.post("do=continue")[0], 202)
        c.close()
        self.assertEqual(self.proc.wait(timeout=300), 0, self.proc.stderr.read().decode())
        rows = events_csv(os.path.join(self.dir, "out"))
        torque = [row for row in rows if row[1] == "driven.torque"]
        self.assertEqual([float(row[2]) for row in torque], [LOAD, LOAD_AT_TARGET], rows)
        # where the page said it was paused (its status gives t to 6 significant digits)
        self.assertLessEqual(abs(float(torque[0][0]) - paused_at), 5e-6 * paused_at)
        self.assertEqual(float(torque[1][0]), target)  # a run to t stops at t exactly
        wet = [row for row in rows if row[1] == "wet"]
        self.assertEqual(len(wet), 1, rows)
        self.assertEqual(wet[0][0], torque[0][0])
        self.assertIn("mu = 0.05 on s in [0.1, 0.3] m", ",".join(wet[0][2:]))
        note = [row for row in rows if row[1] == "note"]
        self.assertEqual([(n[0], n[2]) for n in note], [(torque[0][0], "checkpoint live.ckpt saved from the live view")])
        with open(os.path.join(self.dir, "out", "live.ckpt")) as f:
            self.assertIn("settings", f.read(4000))
        with open(os.path.join(self.dir, "out", "timeseries.csv")) as f:
            self.assertEqual(len(f.read().splitlines()), 1 + round(T_END / SAMPLE) + 1)

    def test_token_page_stream_and_a_client_that_leaves(self):
        self.assertEqual(self.url.hostname, "127.0.0.1")  # bound to loopback unless host is given
        for path in ["/", "/events", "/dygraph.js", "/frame.jpg", "/frame.json", "/?token=" + self.token[:-1], "/?token="]:
            self.assertEqual(self.get(path)[0], 403, path)
        q = "?token=" + self.token
        status, page = self.get("/" + q)
        self.assertEqual(status, 200)
        self.assertIn(b"dygraph.js" + q.encode(), page)
        self.assertEqual(self.get("/dygraph.js" + q)[0], 200)
        self.assertIn(b"Dygraph", self.get("/dygraph.js" + q)[1])
        for path in ["/%2e%2e/%2e%2e/etc/passwd", "/dygraph.min.js", "/index.js", "/src/dygraph.js"]:
            status, said = self.get(path + q)
            self.assertEqual(status, 404, path)
            self.assertIn(b"404: not served", said, path)  # every error says what it is

        c = http.client.HTTPConnection(self.url.hostname, self.url.port, timeout=60)
        c.request("GET", "/events" + q)
        r = c.getresponse()
        self.assertEqual(r.status, 200)
        self.assertEqual(r.getheader("Content-Type"), "text/event-stream")
        columns, times = None, []
        for name, data in events(r):
            if name == "run":
                columns, units = json.loads(data)["columns"], json.loads(data)["units"]
            elif name == "samples":
                for row in json.loads(data):
                    self.assertEqual(len(row), 3 + len(columns))  # t, wall/simulated, step, the columns
                    times.append(row[0])
            if len(times) >= 5 and times[-1] > times[0]:
                break
        self.assertIn("driver.omega", columns)
        # each column's unit, for the page's plot of each unit (io/units.hpp's table)
        self.assertEqual(len(units), len(columns))
        self.assertEqual(units[columns.index("driver.omega")], "rad/s")
        self.assertEqual(units[columns.index("span_driver_driven.tension")], "N")
        self.assertEqual(times, sorted(times))
        self.assertLess(times[-1], T_END)  # read mid-run
        c.close()  # the client leaves mid-run

        self.assert_run_whole()

    def test_a_client_that_reads_nothing_does_not_hold_the_run(self):
        # a page that stopped reading: the stream and a pipeline of picture requests asked for on
        # sockets with the smallest receive buffer, never read; the server's writes to them fill
        # and block, and the run must go on to its end with its outputs whole (the cost of such a
        # client is BM_Serve's "stalled" case, bench/serve_bench.cpp)
        q = "?token=" + self.token
        held = []
        for request in ["GET /events%s HTTP/1.1\r\nHost: x\r\n\r\n" % q,
                        "GET /frame.jpg%s HTTP/1.1\r\nHost: x\r\n\r\n" % q * 200]:
            s = socket.socket()
            s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1024)
            s.connect((self.url.hostname, self.url.port))
            s.sendall(request.encode())
            held.append(s)
        self.addCleanup(lambda: [s.close() for s in held])
        self.assert_run_whole()


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

    def test_a_port_in_use_is_refused(self):
        """a second live view on a port one already listens on is refused, naming the port: from
        another process (--serve PORT) and from the same console (sim:serve{ port = PORT }). Both
        had bound it (cpp-httplib's SO_REUSEPORT) and the requests were split between them"""
        port = self.free_port()
        with open(os.path.join(self.dir, "c.lua"), "w") as f:
            f.write(two_pulley(elements=20) + "sim = drive:start { out = 'c', progress = false }\n")
        holder = subprocess.Popen([BELTSIM, "console", "c.lua", "--serve", str(port)], cwd=self.dir,
                                  stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.addCleanup(lambda: (holder.kill(), holder.wait(), [f.close() for f in (holder.stdin, holder.stdout,
                                                                                   holder.stderr)]))
        for line in holder.stderr:  # it listens once it has printed its address
            if b"live view at " in line:
                break
        p = subprocess.run([BELTSIM, "run", "s.lua", "--serve", str(port)], cwd=self.dir, capture_output=True,
                           text=True, timeout=120)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertIn("port %d is in use" % port, p.stderr)
        self.assertNotIn("live view at", p.stderr)
        # the same console: a simulation of its own served on that port
        out, err = holder.communicate(b"print(pcall(sim.serve, sim, { port = %d }))\nhelp('serve')\n" % port,
                                      timeout=120)
        self.assertEqual(holder.returncode, 0, err)
        self.assertIn("false\tsim:serve: live view: cannot listen on 127.0.0.1:%d: port %d is in use" % (port, port),
                      out.decode())
        # and the help says so: help("serve") at the console, --serve in run's and console's --help
        self.assertIn("a port in use is refused", out.decode())
        for command in ["run", "console"]:
            p = subprocess.run([BELTSIM, command, "--help"], capture_output=True, text=True, timeout=60)
            self.assertIn("a port in use is refused", " ".join(p.stdout.split()), command)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
