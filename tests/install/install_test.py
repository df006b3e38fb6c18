#!/usr/bin/env python3
"""Installing beltsim (docs/install.md): `cmake --install` into a scratch prefix, and the Debian
package CPack makes, unpacked with `dpkg -x` into a scratch root (the machine's own /usr is left
alone, so no `dpkg -i`): each has the program, the example scripts and the docs, and the program
runs an installed example (frames, video and the time series) from a folder outside the source
tree. The package's dependencies must be Debian packages this (Debian) machine has, in the
versions asked: `dpkg -i` here would take it. (That the package installs where nothing else is:
clean_machine_test.py.)

usage: install_test.py BUILD_DIR BELTSIM
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

BUILD = None
BELTSIM = None
SOURCE = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def run(args, **kw):
    """args run to their end (10 min at most), in a session of their own: a timeout or an exception
    here (the clean machine's test ends on a TERM) ends them and all they started (debootstrap's
    and apt's dpkg) before the test removes their folder"""
    with subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                          **kw) as p:
        try:
            out, err = p.communicate(timeout=600)
        except BaseException:
            os.killpg(p.pid, signal.SIGKILL)
            raise
    if p.returncode != 0:
        raise AssertionError("%s failed (%d):\n%s%s" % (" ".join(args), p.returncode, out, err))
    return subprocess.CompletedProcess(args, p.returncode, out, err)


def installed(name):
    """the version of package name installed here, None when it is not"""
    p = subprocess.run(["dpkg-query", "-W", "-f", "${Status}\t${Version}", name], capture_output=True, text=True)
    if p.returncode != 0 or not p.stdout.startswith("install ok installed"):
        return None
    return p.stdout.split("\t")[1]


def satisfied(alternative):
    """'name (>= 1.2)' or 'name' by a package installed here"""
    m = re.fullmatch(r"([a-z0-9][a-z0-9+.-]+)(?::any)?(?:\s*\((<<|<=|=|>=|>>)\s*([^)]+)\))?", alternative.strip())
    if not m:
        raise AssertionError("not a Debian dependency: %r" % alternative)
    version = installed(m.group(1))
    if version is None or not m.group(2):
        return version is not None
    op = {"<<": "lt", "<=": "le", "=": "eq", ">=": "ge", ">>": "gt"}[m.group(2)]
    return subprocess.run(["dpkg", "--compare-versions", version, op, m.group(3)]).returncode == 0


def project_version():
    """the version of CMakeLists.txt's project(), which `beltsim --version` prints"""
    with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
        return re.search(r"project\(beltsim VERSION ([0-9.]+)", f.read()).group(1)


def make_package(build, folder):
    """the Debian package of CPack, made from build's CPackConfig.cmake into folder: its path"""
    run(["cpack", "-G", "DEB", "-B", folder, "--config", os.path.join(build, "CPackConfig.cmake")], cwd=build)
    debs = [f for f in os.listdir(folder) if f.endswith(".deb")]
    if len(debs) != 1:
        raise AssertionError("cpack made %r in %s, not one .deb" % (debs, folder))
    return os.path.join(folder, debs[0])


def check_outputs(test, out, log):
    """out, the folder of a run of paper_dry.lua: the time series, the frames and the video
    (ffprobe finds its video stream where ffmpeg is installed, the test packages' list has it)"""
    with open(os.path.join(out, "timeseries.csv")) as f:
        test.assertGreater(len(f.readlines()), 5)
    frames = os.listdir(os.path.join(out, "frames"))
    test.assertTrue(frames, log)
    for frame in frames:
        with open(os.path.join(out, "frames", frame), "rb") as f:
            test.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n", frame)
    video = os.path.join(out, "paper_dry.mp4")
    test.assertTrue(os.path.getsize(video) > 1000, log)
    with open(video, "rb") as f:
        test.assertEqual(f.read(8)[4:], b"ftyp", video)
    if shutil.which("ffprobe"):
        probe = run(["ffprobe", "-v", "error", "-select_streams", "v", "-show_entries", "stream=codec_name",
                     "-of", "csv=p=0", video]).stdout.split()
        test.assertEqual(probe, ["h264"], video)


class Install(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_install_")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def path(self, *parts):
        return os.path.join(self.dir, *parts)

    def check_tree(self, root):
        """root/bin/beltsim, the examples and the docs; the program runs an example outside the
        source tree"""
        program = os.path.join(root, "bin", "beltsim")
        self.assertTrue(os.access(program, os.X_OK), program)
        self.assertEqual(run([program, "--version"]).stdout.strip(), "beltsim " + project_version())
        share = os.path.join(root, "share")
        for f in ("beltsim/examples/paper_dry.lua", "beltsim/examples/automotive_tensioner.lua",
                  "beltsim/single_node_slurm.py", "doc/beltsim/README.md", "doc/beltsim/docs/sweeps.md",
                  "doc/beltsim/docs/install.md", "doc/beltsim/docs/examples/tutorial/drive.lua"):
            self.assertTrue(os.path.isfile(os.path.join(share, f)), f)
        # every relative link and image of the installed README and docs resolves there
        doc = os.path.join(share, "doc", "beltsim")
        broken = []
        for folder, _, names in os.walk(doc):
            for name in names:
                if not name.endswith(".md"):
                    continue
                page = os.path.join(folder, name)
                with open(page, encoding="utf-8") as f:
                    text = f.read()
                for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", text):
                    if "://" in target or target.startswith("mailto:"):
                        continue
                    if not os.path.exists(os.path.normpath(os.path.join(folder, target))):
                        broken.append(os.path.relpath(page, doc) + ": " + target)
        self.assertEqual(broken, [])
        ldd = run(["ldd", program]).stdout
        self.assertNotIn("not found", ldd)
        # the example copied to a folder of its own, run there: 3 frames, the video, the series
        work = tempfile.mkdtemp(prefix="scenario_", dir=self.dir)
        self.assertFalse(os.path.realpath(work).startswith(SOURCE + os.sep))
        shutil.copy(os.path.join(share, "beltsim", "examples", "paper_dry.lua"), work)
        p = run([program, "run", "paper_dry.lua", "--t-end", "0.01"], cwd=work)
        check_outputs(self, os.path.join(work, "out", "paper_dry"), p.stdout)

    def test_cmake_install(self):
        prefix = self.path("prefix")
        run(["cmake", "--install", BUILD, "--prefix", prefix])
        self.check_tree(prefix)

    def test_debian_package(self):
        deb = make_package(BUILD, self.path("pkg"))
        info = run(["dpkg-deb", "-f", deb, "Package", "Depends"]).stdout
        self.assertIn("Package: beltsim", info)
        depends = info.split("Depends:", 1)[1].strip()
        # (libosmesa6, libegl1 and FFmpeg's are opened at run time, not linked: named by CMakeLists.txt)
        for name in ("liblua5.4-0", "libsundials-cvode6", "libosmesa6", "libnettle8", "fonts-dejavu-core", "libegl1",
                     "libavcodec", "libavformat", "libavutil", "libswscale"):
            self.assertIn(name, depends)
        for group in depends.split(","):
            self.assertTrue(any(satisfied(a) for a in group.split("|")),
                            "no Debian package installed here satisfies %r" % group.strip())
        root = self.path("root")
        run(["dpkg-deb", "-x", deb, root])
        self.assertEqual(sorted(os.listdir(os.path.join(root, "usr"))), ["bin", "share"])
        self.check_tree(os.path.join(root, "usr"))


if __name__ == "__main__":
    BUILD = os.path.abspath(sys.argv.pop(1))
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
