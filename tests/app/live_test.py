#!/usr/bin/env python3
"""The live view's server (docs/live-view.md, src/live/): `beltsim run S.lua --serve` answers 403
without the token printed at its start, serves the page and its plotting library with it and
nothing else, streams samples whose t advances and the renderer's frames (JPEG) while a page is
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
import time
import unittest
import urllib.parse
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = None
T_END = 1.0  # [s] long enough (several seconds of wall time) for the stream to be read mid-run
SAMPLE = 1e-3  # [s] the runs' sample interval: timeseries.csv has T_END / SAMPLE + 1 rows
# [N·m] the torques the page sets on the driven pulley before a run goes on: loads, against its
# clockwise turning (counter-clockwise is positive). What is checked (the torque at the paused time
# in events.csv and session.lua) does not depend on the value; -65 and -60 drove the driven pulley
# the way the driver does, and the drive ran away to 1600 rad/s by t = 1 s: the run on from the
# pause took 6.6 s of CPU where it takes 1.05 s with these (measured on the controls' run alone)
LOAD, LOAD_AT_TARGET = 65, 60


def events(resp):
    """the stream's events as (name, data) pairs, as they arrive"""
    name, data = "message", []
    while True:
        line = resp.readline()
        if not line:
            return
        line = line.decode().rstrip("\n")
        if line == "":
            # a comment alone (the server's ": idle" every half second) is yielded too, so that a
            # reader can give up on what never comes
            yield (name, "\n".join(data)) if data else ("idle", None)
            name, data = "message", []
        elif line.startswith("event: "):
            name = line[7:]
        elif line.startswith("data: "):
            data.append(line[6:])


def status_t(t):
    """t as the page's status gives it (6 significant digits, as %g)"""
    return "%.6g" % t


def events_csv(out):
    with open(os.path.join(out, "events.csv")) as f:
        return [line.split(",") for line in f.read().splitlines()[1:]]


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

    def assert_run_whole(self):
        """the run ends with exit 0 and every sample of timeseries.csv written"""
        self.assertEqual(self.proc.wait(timeout=300), 0, "".join(self.stderr) + self.proc.stderr.read().decode())
        with open(os.path.join(self.dir, "out", "timeseries.csv")) as f:
            rows = f.read().splitlines()
        self.assertEqual(len(rows), 1 + round(T_END / SAMPLE) + 1)  # the header, t = 0 .. T_END
        self.assertAlmostEqual(float(rows[-1].split(",")[0]), T_END, places=12)

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

    def statuses(self, stream):
        """the stream's statuses as they come, and None for each frame event (self.frames: their t)
        and each samples event (self.t: the last sample's t)"""
        self.frames, self.t, self.run, self.status = [], None, None, None
        for name, data in events(stream):
            if name == "run":
                self.run = json.loads(data)
            if name == "status":
                self.status = json.loads(data)
            if name == "idle":
                yield None
            elif name == "frame":
                self.frames.append(json.loads(data))
                yield None
            elif name == "samples" and json.loads(data):
                self.t = json.loads(data)[-1][0]
                yield None
            elif name == "status":
                yield json.loads(data)

    def wait_status(self, it, prefix, within=None):
        """the first status starting with prefix; within: at most that many seconds of wall time
        for a status that may never come (a bound on a failure, not a wait for timing)"""
        end = time.monotonic() + within if within else None
        for status in it:
            if status is not None and status.startswith(prefix):
                return status
            if end and time.monotonic() > end:
                self.fail("no status %r within %g s" % (prefix, within))
        self.fail("the stream ended before a status " + prefix)

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

        self.assertEqual(self.post("do=torque&pulley=nope&value=1"), (202, "queued\n"))
        self.wait_status(it, "refused: no pulley 'nope'")
        self.assertEqual(self.post("do=torque&pulley=driven&value=%r" % LOAD)[0], 202)
        self.wait_status(it, "paused at t = %s s (torque applied)" % status_t(paused_at))
        self.assertEqual(self.post("do=wet&from=0.1&to=99&value=0.05")[0], 202)
        self.assertIn("wet.to: must be in [0, ", self.wait_status(it, "refused: "))
        self.assertEqual(self.post("do=wet&from=0.1&to=0.3&value=0.05")[0], 202)
        self.wait_status(it, "paused at t = %s s (wet applied)" % status_t(paused_at))
        self.assertEqual(self.post("do=save&name=live.ckpt")[0], 202)
        self.wait_status(it, "paused at t = %s s (save applied)" % status_t(paused_at))
        target = round(paused_at + 0.1, 3)
        self.assertEqual(self.post("do=run_to&value=%r" % target)[0], 202)
        self.wait_status(it, "paused at t = %s s" % status_t(target))
        self.assertEqual(self.post("do=torque&pulley=driven&value=%r" % LOAD_AT_TARGET)[0], 202)  # where it paused
        self.wait_status(it, "paused at t = %s s (torque applied)" % status_t(target))
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
                columns = json.loads(data)["columns"]
            elif name == "samples":
                for row in json.loads(data):
                    self.assertEqual(len(row), 3 + len(columns))  # t, wall/simulated, step, the columns
                    times.append(row[0])
            if len(times) >= 5 and times[-1] > times[0]:
                break
        self.assertIn("driver.omega", columns)
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
        live = Live()
        live.url, live.token = url, urllib.parse.parse_qs(url.query)["token"][0]
        c = http.client.HTTPConnection(url.hostname, url.port, timeout=60)
        c.request("GET", "/events?token=" + live.token)
        return live, c, live.statuses(c.getresponse())

    def replay(self, d, session):
        """session (relative to d) run alone in d/replay, which it returns"""
        r = os.path.join(d, "replay")
        os.mkdir(r)
        shutil.copy(os.path.join(d, session), os.path.join(r, "session.lua"))
        p = subprocess.run([BELTSIM, "run", "session.lua"], cwd=r, capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr)
        return r

    def test_page_changes_in_events_and_session(self):
        d, proc = self.console("beltsim_live_console_", subprocess.DEVNULL)
        # the console's commands are waiting on its input before the page does anything
        proc.stdin.write(b"sim:run_to(0.6)\nsim:set_torque('driven', -30)\n")
        proc.stdin.close()
        live, c, it = self.page(proc)
        for _ in it:
            if live.t:
                break
        self.assertEqual(live.post("do=pause")[0], 202)
        paused_at = float(live.wait_status(it, "paused at t = ").split("= ")[1].split(" ")[0])
        self.assertEqual(live.post("do=torque&pulley=driven&value=%r" % LOAD)[0], 202)
        self.assertEqual(live.post("do=wet&from=0.1&to=0.3&value=0.05")[0], 202)
        live.wait_status(it, "paused at t = %s s (wet applied)" % status_t(paused_at))
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
