#!/usr/bin/env python3
"""beltsim stopped from outside: SIGTERM (what timeout, CI cancellation and docker stop send),
SIGKILL, a second signal while stopping, SIGTERM to the console, and a file that cannot grow.
Every case checks that the CSV files hold only whole rows; the video is read back by ffprobe.

usage: kill_test.py BELTSIM [CASE...]   (the cases by name; all but full_file_system when none is
given). Exit status 77 (ctest: skipped) when a case cannot run here, with the reason.
"""
import atexit
import csv
import io
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from scenes import two_pulley  # noqa: E402

BELTSIM = os.path.abspath(sys.argv[1])
TMP = tempfile.mkdtemp(prefix="beltsim_kill_test_")
atexit.register(shutil.rmtree, TMP, True)  # at any exit: a failure or an exception too
FPS, SLOWDOWN = 30, 10  # the frames' defaults: a frame every 1/300 s of simulated time

SCENE = two_pulley(elements=60)
# 3 s of simulated time: about 10 s of wall time with 320x240 frames, so every signal below comes
# in the middle of the run; a stopped run's outputs end before it
T_END = 3
RUN = SCENE + 'drive:run { t_end = %d, progress = false, frames = { size = {320, 240}, video = "v.mp4" } }\n' % T_END
START = SCENE + 'sim = drive:start { progress = false, frames = { size = {320, 240}, video = "v.mp4" } }\n'

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def script(name, text):
    path = os.path.join(TMP, name + ".lua")
    with open(path, "w") as f:
        f.write(text)
    return path


def whole_rows(path):
    """'' when every line of the CSV ends in a newline, has the header's number of fields, and
    (after the header) holds numbers or nan; else what is wrong"""
    with open(path, "rb") as f:
        text = f.read().decode()
    if not text:
        return "empty"
    if not text.endswith("\n"):
        return "the last line has no end: " + repr(text[text.rfind("\n") + 1:])
    lines = list(csv.reader(io.StringIO(text)))
    for k, line in enumerate(lines[1:], 1):
        if len(line) != len(lines[0]):
            return "line %d has %d fields, the header %d: %r" % (k, len(line), len(lines[0]), line)
        if os.path.basename(path) == "timeseries.csv":
            for cell in line:
                try:
                    float(cell)
                except ValueError:
                    return "line %d: %r is not a number" % (k, cell)
    return ""


def size_limit(limit):
    """a child's file-size limit (as on a full disk, write(2) fails, with EFBIG: beltsim ignores SIGXFSZ)"""
    def limited():
        # SIGXFSZ at its default, as a shell leaves it (Python ignores it): beltsim ignores it itself
        signal.signal(signal.SIGXFSZ, signal.SIG_DFL)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return limited


def too_large(p, err, path, what):
    """a run stopped by a file that cannot grow: exit status 1, and the message names the file once"""
    check(p.returncode == 1, "%s: exit status 1 (got %s)" % (what, p.returncode))
    check(err.count("cannot write %s: File too large" % path) == 1,
          "%s: the message names the file, once: %r" % (what, err[-600:]))


def rows(path):
    try:
        with open(path) as f:
            return sum(1 for _ in f) - 1
    except FileNotFoundError:
        return -1


def last_t(path):
    with open(path) as f:
        return float(f.read().rstrip("\n").rsplit("\n", 1)[-1].split(",")[0])


def video_frames(path):
    """frames ffprobe reads (decoding them all), or -1 when it cannot read the file"""
    r = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                        "stream=nb_read_frames", "-of", "csv=p=0", path], capture_output=True, text=True)
    m = re.match(r"\s*(\d+)", r.stdout)
    return int(m.group(1)) if r.returncode == 0 and m else -1


def start(args, out, **kw):
    return subprocess.Popen([BELTSIM] + args + ["--out", out], stderr=subprocess.PIPE, text=True, **kw)


def wait_for(cond, limit, what):
    t0 = time.monotonic()
    while not cond():
        if time.monotonic() - t0 > limit:
            raise SystemExit("gave up waiting for " + what)
        time.sleep(0.02)


def whole_fragments(path):
    """the movie fragments (a 'moof' box and the 'mdat' box after it) wholly in the MP4 file"""
    with open(path, "rb") as f:
        data = f.read()
    pos, n, moof = 0, 0, False
    while pos + 8 <= len(data):
        size, kind = int.from_bytes(data[pos:pos + 4], "big"), data[pos + 4:pos + 8]
        if size == 1 and pos + 16 <= len(data):  # a 64-bit size
            size = int.from_bytes(data[pos + 8:pos + 16], "big")
        if size < 8 or pos + size > len(data):
            break
        if kind == b"moof":
            moof = True
        elif kind == b"mdat" and moof:
            n, moof = n + 1, False
        pos += size
    return n


class Skip(Exception):
    """a case that cannot run here: the reason"""


def outputs_whole(out, label):
    for name in ("timeseries.csv", "events.csv", "parameters.csv"):
        why = whole_rows(os.path.join(out, name))
        check(why == "", "%s: %s holds whole rows %s" % (label, name, why))


def stop_and_wait(p, sigs):
    """sends the signals back to back; returns the exit status"""
    for s in sigs:
        p.send_signal(s)
    p.wait(timeout=30)
    return p.returncode


# ---- SIGTERM: stops at the last finished step, 143, outputs closed --------------------------------
# The stop takes 0.02-0.06 s (measured, also with the other tests busy on both cores: the step
# under way, the encoder's look-ahead drained, the trailer); a second signal ended it in 0.01-0.22 s.
# No wall time is asserted (a loaded machine stretches it): that the run stopped rather than ran on
# is read from its outputs, which end before the 3 s it was asked for (about 7 s of wall time away
# when the signal comes); a run that never stops fails by wait()'s timeout.
def sigterm_run():
    out = os.path.join(TMP, "term")
    p = start(["run", script("run", RUN)], out)
    # the signal comes once the run is under way with frames rendered: 100 rows of the CSV (0.1 s
    # simulated, 30 frames; the scene's build, 0.2 s alone and longer on a loaded machine, comes
    # first, and a signal then would stop the build instead)
    csv_path = os.path.join(out, "timeseries.csv")
    wait_for(lambda: rows(csv_path) > 100, 60, "the run's first 100 rows")
    status = stop_and_wait(p, [signal.SIGTERM])
    err = p.stderr.read()
    check(status == 143, "SIGTERM: exit status 143 (got %s, stderr %r)" % (status, err))
    check("beltsim: terminated; the outputs written so far are kept" in err, "SIGTERM: the message (%r)" % err)
    outputs_whole(out, "SIGTERM")
    n, t = video_frames(os.path.join(out, "v.mp4")), last_t(os.path.join(out, "timeseries.csv"))
    check(t < T_END, "SIGTERM: stopped, not run on: the CSV reaches %.3f s of %g" % (t, T_END))
    # the run stopped at a step end t_s: rows (1 ms apart) reach t <= t_s < t + 1 ms, frames
    # (1/300 s apart) count floor(300 t_s) + 1, so the video has every frame rendered when it has
    # floor(300 t) + 1 of them, or one more
    want = int(t * FPS * SLOWDOWN + 1e-9) + 1
    check(n >= 1 and want <= n <= want + 1,
          "SIGTERM: the video plays every frame rendered: %d, the CSV reaches %.3f s (%d frames)" % (n, t, want))


# ---- SIGKILL: nothing runs, whole rows all the same; the video plays its finished fragments ------
def sigkill_run():
    out = os.path.join(TMP, "kill")
    video = os.path.join(out, "v.mp4")
    p = start(["run", script("run", RUN)], out)
    # the MP4 starts as its header alone and grows by a fragment per second of video (30 frames,
    # first written at about 45 rendered: the encoder looks ahead), each in a few write(2)s; the
    # kill comes once the file holds a whole one (tests/io/writers_test.cpp,
    # KilledWriterLeavesAPlayableFile)
    wait_for(lambda: os.path.exists(video) and whole_fragments(video) >= 1, 60, "the video's first whole fragment")
    stop_and_wait(p, [signal.SIGKILL])
    check(p.returncode == -signal.SIGKILL, "SIGKILL: killed (%s)" % p.returncode)
    outputs_whole(out, "SIGKILL")
    n = video_frames(video)
    check(n >= FPS, "SIGKILL: the video plays its finished fragments: %d frames (>= %d)" % (n, FPS))


# ---- a second signal while stopping: the default action, at once ----------------------------------
# SIGTERM and SIGINT back to back (two of the same kind would merge into one pending signal): the
# one handled second comes while the first one's stop is under way, and ends the process by its
# default action. The two may be handled at once by two threads (the encoder's, llvmpipe's): before
# the handler claimed the stop by an atomic exchange, both could take it, and the run ended as for one
# signal, 130 or 143 (3 of 210 runs under load; 0 of 210 with the exchange).
def second_signal():
    out = os.path.join(TMP, "twice")
    p = start(["run", script("run", RUN)], out)
    wait_for(lambda: rows(os.path.join(out, "timeseries.csv")) > 10, 10, "the first rows")
    status = stop_and_wait(p, [signal.SIGTERM, signal.SIGINT])
    err = p.stderr.read()
    check(status in (-signal.SIGINT, -signal.SIGTERM), "second signal: ended by the default action (%s)" % status)
    # not silent: one line says it quit without finishing the outputs, and what they hold (a user's
    # second Ctrl-C ended with exit 130 and no word, parameters.csv without its end rows)
    said = re.findall(r"beltsim: (?:Ctrl-C|SIGTERM) while stopping: quitting at once, without finishing the outputs: "
                      r"their rows so far are kept whole, but parameters\.csv gets no end rows and a video holds "
                      r"only its finished fragments\n", err)
    check(len(said) == 1, "second signal: one line says so (%r)" % err[-600:])
    outputs_whole(out, "second signal")


# ---- the console: SIGTERM during sim:run_to closes every output and exits 143 ---------------------
def console():
    out = os.path.join(TMP, "console")
    p = start(["console", script("start", START)], out, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, cwd=TMP)
    p.stdin.write("sim:run_to(%d)\nprint('not reached')\n" % T_END)
    p.stdin.flush()  # stdin stays open: the console would wait for more after the run
    wait_for(lambda: rows(os.path.join(out, "timeseries.csv")) > 100, 10, "the console's run")
    status = stop_and_wait(p, [signal.SIGTERM])
    err = p.stderr.read()
    check(status == 143, "console SIGTERM: exit status 143 (got %s, stderr %r)" % (status, err))
    check("terminated" in err, "console SIGTERM: the message (%r)" % err)
    outputs_whole(out, "console SIGTERM")
    t = last_t(os.path.join(out, "timeseries.csv"))
    check(t < T_END, "console SIGTERM: stopped, not run on: the CSV reaches %.3f s of %g" % (t, T_END))
    check(video_frames(os.path.join(out, "v.mp4")) >= 1, "console SIGTERM: the video plays")
    # (session.lua goes to out/<script>/ in the working directory whatever --out says)
    sessions = [os.path.join(d, "session.lua") for d in (out, os.path.join(TMP, "out", "start"))]
    check(any(os.path.exists(f) for f in sessions), "console SIGTERM: session.lua written")


# ---- a file that cannot grow (a full disk; here a file-size limit, which fails write(2) the same
# way): exit 1, the message names the file, the rows that fitted are whole ----------------------
def full_disk():
    out = os.path.join(TMP, "full")
    limit = 64 * 1024  # parameters.csv (3 KiB) fits; timeseries.csv reaches it in about 0.4 s simulated

    p = start(["run", script("run", RUN), "--no-frames"], out, preexec_fn=size_limit(limit))
    p.wait(timeout=60)
    err = p.stderr.read()
    csv = os.path.join(out, "timeseries.csv")
    too_large(p, err, csv, "full disk")
    check(whole_rows(csv) == "" and os.path.getsize(csv) > limit - 1024, "full disk: the rows that fitted, whole")
    stopped_as_said(err, out, "full disk")


def stopped_as_said(err, out, what):
    """a run stopped by an output that cannot be written says where it stopped and that the outputs
    so far are kept, and parameters.csv says how it ended (a user's full disk gave neither)"""
    m = re.search(r"; the run stopped at t = ([0-9.e-]+) s of [0-9.e-]+ s, and the outputs written so far are kept, their "
                  r"rows whole \(timeseries\.csv up to t = ([0-9.e-]+) s\)", err)
    check(m is not None, "%s: the message says where the run stopped and what is kept: %r" % (what, err[-600:]))
    with open(os.path.join(out, "parameters.csv")) as f:
        params = f.read()
    last = last_t(os.path.join(out, "timeseries.csv"))
    check(m is not None and abs(float(m.group(2)) - last) <= 1e-9 * max(1, last),
          "%s: the message's last row is the CSV's (%s, %r)" % (what, last, m and m.group(2)))
    check(re.search(r"\nend\.last_row_t,%r,s,derived," % last, params) is not None
          and "\nend.status,failed,,derived,\"cannot write " in params,
          "%s: parameters.csv ends with how the run ended: %r" % (what, params[-700:]))



# ---- the same in the console: the error at the prompt names the file once, and the exit does not
# name it again (it did, as an output lost that no message had shown); exit 1 ---------------------
def full_disk_console():
    out = os.path.join(TMP, "full_console")
    limit = 64 * 1024
    start_text = SCENE + 'sim = drive:start { progress = false }\n'

    p = start(["console", script("full_console", start_text)], out, stdin=subprocess.PIPE,
              stdout=subprocess.DEVNULL, cwd=TMP, preexec_fn=size_limit(limit))
    p.stdin.write("sim:run_to(1)\n")
    p.stdin.close()
    p.wait(timeout=60)
    err = p.stderr.read()
    csv = os.path.join(out, "timeseries.csv")
    too_large(p, err, csv, "full disk, console")
    check(whole_rows(csv) == "", "full disk, console: the rows that fitted, whole")


# ---- the video cannot grow: frames are written on a thread of their own (render/recorder.cpp),
# so the failure comes back to the run from there. Exit 1, the message names the video, which
# plays its whole fragments, and the CSV holds whole rows --------------------------------------
def full_disk_video():
    out = os.path.join(TMP, "full_video")
    limit = 200 * 1024  # at 640x360 the video passes it before 0.4 s simulated, the CSV after 1 s
    run = script("full_video", SCENE + 'drive:run { t_end = 1, progress = false, frames = { size = {640, 360}, '
                                       'video = "v.mp4", png_every = 1000 } }\n')

    p = start(["run", run], out, preexec_fn=size_limit(limit))
    p.wait(timeout=60)
    err = p.stderr.read()
    video = os.path.join(out, "v.mp4")
    too_large(p, err, video, "full disk, video")
    n = video_frames(video)
    check(n >= FPS, "full disk, video: it plays its whole fragments: %d frames (>= %d)" % (n, FPS))
    check(whole_rows(os.path.join(out, "timeseries.csv")) == "", "full disk, video: the CSV's rows whole")


# ---- a file system that is full: a 128 KiB tmpfs (root and mount(2) needed: skipped with the
# reason otherwise). Exit 1, the message names the file and "No space left on device", and what
# was written before is kept: the CSV is, row for row, the start of the same run's CSV on a disk
# with room -------------------------------------------------------------------------------------
def full_file_system():
    mnt = os.path.join(TMP, "tmpfs")
    os.makedirs(mnt)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=128k", "tmpfs", mnt], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT)
    if r.returncode != 0:
        raise Skip("full file system: cannot mount a tmpfs here (%s); the file-size limit (full_disk) stands in "
                   "for it" % r.stdout.decode().strip())
    try:
        # 0.4 s: the CSV grows to about 230 KB, so the 128 KiB fill at about 0.23 s, and the run with
        # room, the reference, runs only as far as is compared
        run = script("full_fs", SCENE + 'drive:run { t_end = 0.4, progress = false }\n')
        full = os.path.join(mnt, "out")
        p = start(["run", run, "--no-frames"], full)
        p.wait(timeout=120)
        err = p.stderr.read()
        room = os.path.join(TMP, "room")
        q = start(["run", run, "--no-frames"], room)
        q.wait(timeout=120)
        check(q.returncode == 0, "full file system: the run with room ends well (%s)" % q.stderr.read())
        check(p.returncode == 1, "full file system: exit status 1 (got %s)" % p.returncode)
        named = re.search(r"cannot write (%s/\S+): No space left on device" % re.escape(full), err)
        check(named is not None, "full file system: the message names the file and the reason: %r" % err)
        csv = os.path.join(full, "timeseries.csv")
        with open(csv, "rb") as f:
            written = f.read()
        with open(os.path.join(room, "timeseries.csv"), "rb") as f:
            reference = f.read()
        check(whole_rows(csv) == "" and len(written) > 64 * 1024,
              "full file system: whole rows, %d bytes of them" % len(written))
        check(reference.startswith(written), "full file system: nothing written before is lost or changed")
        with open(os.path.join(full, "parameters.csv"), "rb") as f:
            params = f.read()
        with open(os.path.join(room, "parameters.csv"), "rb") as f:
            ref_params = f.read()
        # the model's rows as the run with room has them (the warning.* and end.* rows, added at the
        # end, count what each run met before it ended and say how it ended; run.out is each run's
        # own folder)
        def model_rows(text):
            return [r for r in text.split(b"\n") if not r.startswith((b"warning.", b"end.", b"run.out,"))]
        check(model_rows(params) == model_rows(ref_params) and len(model_rows(params)) > 40 and params.endswith(b"\n"),
              "full file system: parameters.csv as it was written before the disk filled")
        # its end rows found the room parameters.csv kept for them on the full disk
        stopped_as_said(err, full, "full file system")
        # and the run said before it ran that its outputs would not fit (statvfs of the folder)
        check(re.search(r"beltsim: warning: the outputs in %s will grow by about [0-9.]+ kB by t = 0\.4 s "
                        r"\(timeseries\.csv: 400 rows of about \d+ bytes\): that is more than the [0-9.]+ kB free "
                        r"on the file system that holds it: the run will stop with an error when the disk is full"
                        % re.escape(full), err) is not None,
              "full file system: the warning before the run: %r" % err[-900:])
    finally:
        subprocess.run(["umount", mnt])


CASES = (sigterm_run, sigkill_run, second_signal, console, full_disk, full_disk_console, full_disk_video,
         full_file_system)
names = sys.argv[2:] or [c.__name__ for c in CASES if c is not full_file_system]
unknown = [n for n in names if n not in [c.__name__ for c in CASES]]
if unknown:
    raise SystemExit("unknown case %s; the cases: %s" % (", ".join(unknown), " ".join(c.__name__ for c in CASES)))
t0 = time.monotonic()
skipped = []
for case in CASES:
    if case.__name__ in names:
        try:
            case()
        except Skip as e:
            print("skip " + str(e))
            skipped.append(case.__name__)
print("%.1f s" % (time.monotonic() - t0))
if failures:
    print("%d failed" % len(failures))
    sys.exit(1)
if skipped:
    sys.exit(77)
