#!/usr/bin/env python3
"""beltsim's outputs from the outside (io/output_dir.hpp):
- a symbolic link planted under the name of every file beltsim names itself (timeseries.csv,
  events.csv, snapshots.csv, parameters.csv, frames/frame_00000.png and the frames folder, the video,
  a checkpoint, session.lua, plot.png, wp.png) is refused: exit status 1, the message names the file,
  the link's target is untouched (as a scenario package shipping `events.csv -> ~/.bashrc` would try),
  and a file given by its bare name is named as given (`taken.csv`, not `./taken.csv`);
- one writer per output folder: a run while a console's simulation holds the folder, two live
  simulations of one script, a checkpoint resumed twice are refused with a clear message;
- an output that cannot be written (a file-size limit, which fails write(2) as a full disk does)
  makes the exit status non-zero and names the file: parameters.csv at close, session.lua (never
  reported as written), the video (cut to its whole fragments, which play), a checkpoint (no
  .part left behind).

usage: outputs_test.py BELTSIM
"""
import atexit
import os
import select
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
TMP = tempfile.mkdtemp(prefix="beltsim_outputs_test_")
atexit.register(shutil.rmtree, TMP, True)  # at any exit: a failure or an exception too
SECRET = "export PATH=/usr/bin  # the user's own file\n"
LINK = "it is a symbolic link (beltsim never writes through a link)"

SCENE = two_pulley(elements=60)

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


def fresh(name):
    d = os.path.join(TMP, name)
    os.makedirs(d)
    return d


def beltsim(args, limit=None, stdin=None, cwd=None, timeout=120):
    def limited():
        # SIGXFSZ at its default, as a shell leaves it (Python ignores it): beltsim ignores it itself
        signal.signal(signal.SIGXFSZ, signal.SIG_DFL)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    r = subprocess.run([BELTSIM] + args, input=stdin, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       preexec_fn=limited if limit else None, cwd=cwd, timeout=timeout,
                       env=dict(os.environ, BELTSIM_TERM_IMAGES="off", BELTSIM_HISTORY=os.path.join(TMP, "history")))
    return r.returncode, r.stderr


def read(path):
    with open(path) as f:
        return f.read()


def plant(folder, name):
    """folder/name -> a file outside folder holding SECRET; returns the target"""
    target = os.path.join(os.path.dirname(folder.rstrip("/")), "target_" + name.replace("/", "_"))
    with open(target, "w") as f:
        f.write(SECRET)
    os.makedirs(os.path.dirname(os.path.join(folder, name)), exist_ok=True)
    os.symlink(target, os.path.join(folder, name))
    return target


def refused(label, status, err, path, target, shown=None):
    check(status == 1, "%s: exit status 1 (got %s)" % (label, status))
    check("cannot write %s: %s" % (shown or path, LINK) in err, "%s: the message names the file: %r" % (label, err[-400:]))
    check(read(target) == SECRET, "%s: the link's target is untouched" % label)
    check(os.path.islink(path), "%s: the link is left as it was" % label)


RUN = SCENE + 'drive:run { t_end = 0.004, progress = false, snapshots = { every = 0.002 } }\n'
FRAMES = SCENE + ('drive:run { t_end = 0.004, progress = false, frames = { size = {64, 48}, png = true, '
                  'video = "v.mp4" } }\n')


# ---- §1 a planted link under every fixed name --------------------------------------------------
def planted_links():
    for name in ("timeseries.csv", "events.csv", "snapshots.csv", "parameters.csv"):
        out = fresh("link_" + name)
        target = plant(out, name)
        status, err = beltsim(["run", script("run", RUN), "--no-frames", "--out", out])
        refused(name, status, err, os.path.join(out, name), target)
    for name in ("frames/frame_00000.png", "v.mp4"):
        out = fresh("link_" + name.replace("/", "_"))
        target = plant(out, name)
        status, err = beltsim(["run", script("frames", FRAMES), "--out", out])
        refused(name, status, err, os.path.join(out, name), target)
    # the frames folder itself
    out = fresh("link_frames_folder")
    elsewhere = fresh("elsewhere")
    os.symlink(elsewhere, os.path.join(out, "frames"))
    status, err = beltsim(["run", script("frames", FRAMES), "--out", out])
    check(status == 1 and "cannot write %s/frames: %s" % (out, LINK) in err, "frames folder: refused: %r" % err[-300:])
    check(os.listdir(elsewhere) == [], "frames folder: nothing written through it")
    # a checkpoint
    out = fresh("link_ckpt")
    target = plant(out, "run.ckpt")
    ck = os.path.join(out, "run.ckpt")
    status, err = beltsim(["run", script("save", SCENE + 'local sim = drive:start { progress = false }\n'
                                         'sim:run_to(0.002)\nsim:save(%r)\n' % ck), "--out", out])
    refused("run.ckpt", status, err, ck, target)
    check(not os.path.exists(ck + ".part"), "run.ckpt: no .part left")
    # the console's session.lua: a name that is taken, a link too, is left alone (the session's
    # commands go to session_2.lua)
    out = fresh("link_session")
    target = plant(out, "session.lua")
    status, err = beltsim(["console", "--out", out], stdin="x = 1\n")
    check(status == 0, "session.lua: a console beside a planted link ends well (%r)" % err[-300:])
    check("the session's commands are in %s" % os.path.join(out, "session_2.lua") in err,
          "session.lua: the commands go to session_2.lua (%r)" % err[-300:])
    check(read(target) == SECRET, "session.lua: the link's target is untouched")
    check(os.path.islink(os.path.join(out, "session.lua")), "session.lua: the link is left as it was")
    # beltsim plot's picture, beside the CSV
    out = fresh("link_plot")
    status, err = beltsim(["run", script("run", RUN), "--no-frames", "--out", out])
    check(status == 0, "plot: the run for it ends well (%r)" % err[-300:])
    target = plant(out, "plot.png")
    status, err = beltsim(["plot", os.path.join(out, "timeseries.csv")])
    refused("plot.png", status, err, os.path.join(out, "plot.png"), target)
    # wp's picture (wp.csv is written, the picture is refused: exit 1 all the same)
    out = fresh("link_wp")
    target = plant(out, "wp.png")
    status, err = beltsim(["wp", script("wp", SCENE + 'drive:run { t_end = 0.01, progress = false }\n'),
                           "--integrators", "rkf45", "--rtols", "1e-3", "--ref-rtol", "1e-5", "--out", out])
    refused("wp.png", status, err, os.path.join(out, "wp.png"), target)
    # wp's folder itself a link: refused before a run, nothing written through it (it was made
    # and followed by create_directories)
    out = fresh("link_wp_folder")
    elsewhere = fresh("wp_elsewhere")
    os.symlink(elsewhere, os.path.join(out, "study"))
    status, err = beltsim(["wp", script("wp", SCENE + 'drive:run { t_end = 0.01, progress = false }\n'),
                           "--integrators", "rkf45", "--rtols", "1e-3", "--ref-rtol", "1e-5", "--out",
                           os.path.join(out, "study")])
    check(status == 1 and LINK in err, "wp folder: refused: %r" % err[-300:])
    check(os.listdir(elsewhere) == [], "wp folder: nothing written through it")
    # the shape of the attack: a scenario package whose own folder (an allowed output folder) holds
    # events.csv -> the user's start-up file, and a script that logs shell syntax into it
    package = fresh("package")
    target = plant(package, "events.csv")
    attack = script_in(package, "scenario.lua", SCENE + 'local sim = drive:start { out = ".", progress = false }\n'
                       'sim:log("$(touch /tmp/pwned)")\nsim:close()\n')
    status, err = beltsim(["run", attack], cwd=package)
    refused("the scenario package", status, err, os.path.join(package, "events.csv"), target, shown="./events.csv")
    # a file given by its bare name is named as given, not "./taken.csv": beltsim summary's CSV
    # (written in place) and picture (written whole), each over a planted link and over a folder
    run_dir = fresh("bare_names_run")
    status, err = beltsim(["run", script("run", RUN), "--no-frames", "--out", run_dir])
    check(status == 0, "bare names: the run for them ends well (%r)" % err[-300:])
    for option, name in (("--csv", "taken.csv"), ("--plot", "taken.png")):
        here = fresh("bare_" + name)
        target = plant(here, name)
        status, err = beltsim(["summary", run_dir, option, name], cwd=here)
        refused("summary " + option + " " + name, status, err, os.path.join(here, name), target, shown=name)
        os.remove(os.path.join(here, name))
        os.mkdir(os.path.join(here, name))
        status, err = beltsim(["summary", run_dir, option, name], cwd=here)
        check(status == 1 and re.search(r"beltsim summary: cannot write %s: (Is a directory|it is a folder)\n"
                                        % re.escape(name), err) is not None,
              "summary %s %s over a folder: named as given: %r" % (option, name, err[-300:]))


def script_in(folder, name, text):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


# ---- §4 one writer per output folder -------------------------------------------------------------
def one_writer():
    out = fresh("busy")
    console = subprocess.Popen([BELTSIM, "console", "--out", out], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True,
                               env=dict(os.environ, BELTSIM_HISTORY=os.path.join(TMP, "history")))
    # the console prints the marker once start has returned: the simulation holds the folder and
    # has written its first row (events.csv appears earlier, before that row)
    console.stdin.write(SCENE.replace("local drive", "drive") + "sim = drive:start { progress = false }\n"
                        "print('console: started')\n")
    console.stdin.flush()
    t0 = time.monotonic()
    while True:
        ready, _, _ = select.select([console.stdout], [], [], 1.0)
        if time.monotonic() - t0 > 60 or console.poll() is not None:
            raise SystemExit("the console's simulation never started")
        if ready and "console: started" in console.stdout.readline():
            break
    rows = read(os.path.join(out, "timeseries.csv"))
    status, err = beltsim(["run", script("run", RUN), "--no-frames", "--out", out])
    check(status == 1 and ("the output folder %s is in use by another beltsim (process %d)" % (out, console.pid)) in err,
          "a run while a console's simulation holds the folder: refused, naming the process: %r" % err[-300:])
    check(read(os.path.join(out, "timeseries.csv")) == rows, "the console's rows are untouched")
    console.stdin.write("sim:close()\n")
    console.stdin.close()
    console.wait(timeout=60)
    status, err = beltsim(["run", script("run", RUN), "--no-frames", "--out", out])
    check(status == 0, "once the console is done, the folder is free (%r)" % err[-300:])

    out = fresh("two_live")
    status, err = beltsim(["run", script("two_live", SCENE + 'local a = drive:start { progress = false }\n'
                                         'local b = drive:start { progress = false }\n'), "--out", out])
    check(status == 1 and re.search(r"two_live\.lua:\d+: .*the output folder %s is in use by another simulation of "
                                    r"this beltsim" % re.escape(out), err) is not None,
          "two live simulations of one script: the second refused with file:line: %r" % err[-300:])

    out = fresh("resume_twice")
    ck = os.path.join(out, "run.ckpt")
    status, err = beltsim(["run", script("resume_twice", SCENE + 'local s = drive:start { progress = false }\n'
                                         's:run_to(0.002)\ns:save(%r)\ns:close()\n'
                                         'local a = beltsim.resume(%r)\nlocal b = beltsim.resume(%r)\n'
                                         % (ck, ck, ck)), "--out", out])
    check(status == 1 and "is in use by another simulation of this beltsim" in err,
          "a checkpoint resumed twice: the second refused: %r" % err[-300:])
    # the first one says what it continued, from when, and where its outputs go
    check("beltsim: %s resumed at t = 0.002 s; its outputs go on in %s\n" % (ck, out) in err,
          "a resumed checkpoint is announced with its time and folder: %r" % err[-600:])
    # --out was the script's scene:start's; the resumed simulation keeps its checkpoint's folder
    check("beltsim: warning: --out applies to scene:run and scene:start only; the simulation beltsim.resume continues "
          "keeps its checkpoint's settings" in err, "the command line's options are said not to reach a resume: %r"
          % err[-600:])

    # run from the folder that holds its outputs, a resumed run names them as the run that wrote them
    # did (the checkpoint keeps the folder absolute, so that a run resumed from elsewhere finds it)
    fresh("resume_here")
    status, err = beltsim(["run", script("resume_here", SCENE + 'local s = drive:start {}\ns:run_to(0.002)\n'
                                         's:save("run.ckpt")\ns:close()\n'
                                         'local r = beltsim.resume("resume_here/run.ckpt")\n'
                                         'r:run_to(0.003)\nr:close()\n'), "--out", "resume_here"], cwd=TMP)
    check(status == 0 and "its outputs go on in resume_here\n" in err
          and re.search(r"run ended at t = 0\.003 s \(\d+ steps?, [^)]*\): resume_here/\n", err) is not None,
          "a resumed run in the folder beltsim runs in names its outputs relative to it, as the first run: %r"
          % err[-600:])


# ---- §6 outputs that cannot be written -----------------------------------------------------------
def not_written():
    # parameters.csv at close: the limit lets its first write through, not the warning rows added
    # at close; the samples of 5 ms stay far below it
    room = fresh("room")
    short = script("short", SCENE + 'drive:run { t_end = 0.005, progress = false }\n')
    status, err = beltsim(["run", short, "--out", room])
    check(status == 0, "a short run with room ends well (%r)" % err[-300:])
    first = sum(len(line) + 1 for line in read(os.path.join(room, "parameters.csv")).split("\n")[:-1]
                if not line.startswith("warning."))
    check(os.path.getsize(os.path.join(room, "timeseries.csv")) < first, "the samples stay below parameters.csv")
    out = fresh("params_at_close")
    status, err = beltsim(["run", short, "--out", out], limit=first + 16)
    check(status == 1 and "cannot write %s/parameters.csv: File too large" % out in err,
          "parameters.csv at close: exit 1 naming it (got %s, %r)" % (status, err[-300:]))

    # session.lua: the limit is below its first line
    out = fresh("session_full")
    status, err = beltsim(["console", "--out", out], stdin="x = 1\n", limit=64)
    check(status == 1 and "cannot write %s/session.lua: File too large" % out in err,
          "session.lua: exit 1 naming it (got %s, %r)" % (status, err[-300:]))
    check("the session's commands are in" not in err, "session.lua: not reported as written")
    check(os.listdir(out) == [], "session.lua: neither an empty one nor a .part left: %r" % os.listdir(out))

    # the video: cut at its last whole fragment, which plays; named; exit 1
    out = fresh("video_full")
    limit = 96 * 1024  # past the first whole fragment (a second of video: about 50 KB)
    status, err = beltsim(["run", script("video", SCENE + 'drive:run { t_end = 1, progress = false, sample = 0.1, '
                                         'frames = { size = {320, 240}, video = "v.mp4" } }\n'), "--out", out],
                          limit=limit)
    video = os.path.join(out, "v.mp4")
    check(status == 1 and "cannot write %s: File too large" % video in err,
          "video: exit 1 naming it (got %s, %r)" % (status, err[-300:]))
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames", "-of", "csv=p=0", video], capture_output=True, text=True)
    frames = int(probe.stdout.strip() or 0) if probe.returncode == 0 else -1
    check(frames > 0 and probe.stderr == "" and os.path.getsize(video) < limit,
          "video: its whole fragments play, no torn one (%d frames, %d bytes, ffprobe says %r)"
          % (frames, os.path.getsize(video), probe.stderr[-300:]))

    # a checkpoint that does not fit: named, and no .part left
    out = fresh("ckpt_full")
    ck = os.path.join(out, "run.ckpt")
    status, err = beltsim(["run", script("save_full", SCENE + 'local sim = drive:start { progress = false }\n'
                                         'sim:run_to(0.002)\nsim:save(%r)\n' % ck), "--out", out], limit=8192)
    check(status == 1 and "cannot write %s: File too large" % ck in err,
          "checkpoint: exit 1 naming it (got %s, %r)" % (status, err[-300:]))
    check(not os.path.exists(ck) and not os.path.exists(ck + ".part"), "checkpoint: no half file, no .part")


t0 = time.monotonic()
for case in (planted_links, one_writer, not_written):
    case()
print("%.1f s" % (time.monotonic() - t0))
if failures:
    print("%d failed" % len(failures))
    sys.exit(1)
