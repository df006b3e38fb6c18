"""Shared by the live view's tests (live_test.py, live_console_test.py): the runs' sample interval
and the page's torques, the stream's events, events.csv, and a page's requests and statuses."""
import http.client
import json
import os
import time

SAMPLE = 1e-3  # [s] the runs' sample interval
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


class Page:
    """a live view's page as a client sees it: url (its address) and token, which a test sets"""

    def fail(self, msg):
        """as a TestCase's (a Page that is a TestCase too has that one)"""
        raise AssertionError(msg)

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
