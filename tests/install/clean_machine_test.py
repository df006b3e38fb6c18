#!/usr/bin/env python3
"""The Debian package of CPack installed on a clean machine (docs/install.md): a minimal Debian of
this machine's release made by `debootstrap --variant=minbase` in BUILD_DIR/clean_machine/root,
with Debian's archive alone in its apt sources, where `apt-get install --no-install-recommends
./beltsim_*.deb` must find every dependency, and nothing else is installed. Then, in that root,
`beltsim --version`, `ldd` (every library found) and the installed paper_dry.lua copied to
/root/work (no source tree in that machine) run with OSMesa and with EGL, their frames alike, the
video read back by the host's ffprobe, and `beltsim plot` (gnuplot). Nothing is mounted in the
root, so removing it cannot reach the host; the host's /usr is not touched. Its folder is removed
at the end, pass or fail, and at the start if a killed run left it.

Needs root (debootstrap, chroot), debootstrap (scripts/debian-packages-test.txt) and the Debian
archive on the network (BELTSIM_DEBIAN_MIRROR, default http://deb.debian.org/debian, and
BELTSIM_DEBIAN_SECURITY for its security updates); without root or debootstrap it is skipped
(77). 3.5-6 min on two cores (label clean_machine: scripts/setup.sh clean-machine-test).

usage: clean_machine_test.py BUILD_DIR
"""
import os
import shutil
import signal
import subprocess
import sys
import time
import unittest

from install_test import check_outputs, make_package, project_version, run

BUILD = None
# the chroot's environment: nothing of the host's (its PATH, its locale, the build's variables)
CHROOT_ENV = ["env", "-i", "PATH=/usr/sbin:/usr/bin:/sbin:/bin", "HOME=/root", "LANG=C.UTF-8",
              "DEBIAN_FRONTEND=noninteractive"]


def codename():
    """this machine's Debian release (bookworm): the package is built for it (docs/install.md)"""
    with open("/etc/os-release") as f:
        fields = dict(line.rstrip("\n").split("=", 1) for line in f if "=" in line)
    return fields["VERSION_CODENAME"].strip('"')


def mounts_under(folder):
    """the mount points at or under folder (/proc/self/mounts): none, since the test mounts nothing;
    one there would make removing the folder reach outside it"""
    folder = os.path.realpath(folder)
    with open("/proc/self/mounts") as f:
        points = [line.split()[1].replace("\\040", " ") for line in f]
    return [p for p in points if p == folder or p.startswith(folder + os.sep)]


def remove(folder):
    if not os.path.lexists(folder):
        return
    found = mounts_under(folder)
    if found:
        raise AssertionError("not removing %s: mounted under it: %s" % (folder, ", ".join(found)))
    shutil.rmtree(folder)


class CleanInstall(unittest.TestCase):
    def setUp(self):
        if os.geteuid() != 0:
            self.skipTest("needs root (debootstrap, chroot)")
        if not shutil.which("debootstrap"):
            self.skipTest("needs debootstrap (apt install debootstrap; scripts/debian-packages-test.txt)")
        self.dir = os.path.join(BUILD, "clean_machine")
        remove(self.dir)  # a killed run's
        os.makedirs(self.dir)
        self.addCleanup(self.finish)
        self.root = os.path.join(self.dir, "root")
        self.last = time.monotonic()

    def chroot(self, *command, **kw):
        return run(["chroot", self.root] + CHROOT_ENV + list(command), **kw)

    def finish(self):
        self.last = time.monotonic()
        remove(self.dir)
        self.lap("the folder removed")

    def lap(self, what):
        """what was done since the last lap, and how long it took"""
        now = time.monotonic()
        print("%s: %.0f s" % (what, now - self.last), flush=True)
        self.last = now

    def test_install_and_run(self):
        deb = make_package(BUILD, os.path.join(self.dir, "pkg"))
        self.lap("cpack")
        mirror = os.environ.get("BELTSIM_DEBIAN_MIRROR", "http://deb.debian.org/debian")
        security = os.environ.get("BELTSIM_DEBIAN_SECURITY", "http://deb.debian.org/debian-security")
        suite = codename()
        run(["debootstrap", "--variant=minbase", suite, self.root, mirror])
        self.lap("debootstrap --variant=minbase " + suite)
        # Debian's archive alone, with its updates (the build's libraries may come from them)
        with open(os.path.join(self.root, "etc/apt/sources.list"), "w") as f:
            f.write("deb %s %s main\ndeb %s %s-updates main\ndeb %s %s-security main\n" %
                    (mirror, suite, mirror, suite, security, suite))
        shutil.copy("/etc/resolv.conf", os.path.join(self.root, "etc/resolv.conf"))
        # no service starts in the chroot (invoke-rc.d asks policy-rc.d; 101: not allowed)
        with open(os.path.join(self.root, "usr/sbin/policy-rc.d"), "w") as f:
            f.write("#!/bin/sh\nexit 101\n")
        os.chmod(os.path.join(self.root, "usr/sbin/policy-rc.d"), 0o755)
        self.assertFalse(os.path.exists(os.path.join(self.root, "usr/bin/beltsim")))
        shutil.copy(deb, os.path.join(self.root, "tmp"))
        self.chroot("apt-get", "update", "-q")
        self.lap("apt-get update")
        self.chroot("apt-get", "install", "-y", "-q", "--no-install-recommends", "/tmp/" + os.path.basename(deb))
        self.lap("apt-get install ./" + os.path.basename(deb))
        status = self.chroot("dpkg-query", "-W", "-f", "${Status} ${Version}", "beltsim").stdout
        self.assertEqual(status, "install ok installed " + project_version())

        self.assertEqual(self.chroot("beltsim", "--version").stdout.strip(), "beltsim " + project_version())
        ldd = self.chroot("ldd", "/usr/bin/beltsim").stdout
        self.assertNotIn("not found", ldd)
        # the installed example, run in a folder of its own: no source tree on this machine
        self.chroot("mkdir", "-p", "/root/work")
        self.chroot("cp", "/usr/share/beltsim/examples/paper_dry.lua", "/root/work/")
        work = os.path.join(self.root, "root/work")
        sh = ["sh", "-c", 'cd /root/work && exec "$@"', "sh"]
        p = self.chroot(*sh, "beltsim", "run", "paper_dry.lua", "--t-end", "0.01")
        check_outputs(self, os.path.join(work, "out", "paper_dry"), p.stdout + p.stderr)
        # the EGL backend (libegl1, libegl-mesa0, libgl1-mesa-dri): the same pixels as OSMesa's
        p = self.chroot("env", "BELTSIM_GL=egl", *sh, "beltsim", "run", "paper_dry.lua", "--t-end", "0.01",
                        "--out", "egl")
        check_outputs(self, os.path.join(work, "egl"), p.stdout + p.stderr)
        self.chroot(*sh, "beltsim", "compare", "egl/frames/frame_00000.png",
                    "out/paper_dry/frames/frame_00000.png")
        # beltsim plot runs gnuplot (gnuplot-nox)
        self.chroot(*sh, "beltsim", "plot", "out/paper_dry/timeseries.csv", "--out", "plot.png")
        with open(os.path.join(work, "plot.png"), "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.lap("beltsim --version, ldd, run (OSMesa, EGL), compare, plot")


if __name__ == "__main__":
    BUILD = os.path.abspath(sys.argv.pop(1))
    # a TERM ends the test through its clean-up (a KILL, as ctest's timeout sends, leaves the
    # folder to the next run)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    result = unittest.main(verbosity=2, exit=False).result
    # skipped (no root, no debootstrap) is a skip for CTest (SKIP_RETURN_CODE 77), not a pass
    sys.exit(1 if not result.wasSuccessful() else 77 if result.skipped else 0)
