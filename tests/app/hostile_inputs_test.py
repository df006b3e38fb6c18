#!/usr/bin/env python3
"""`beltsim compare` and `beltsim plot` on files that are not what they claim (issue 45 §7): a PNG
whose header claims more pixels than its bytes can hold is refused before anything is allocated,
a FIFO or a device named as a PNG, a CSV file or a script is refused without blocking, a CSV file of many
columns is read in time linear in them, and the exit status of compare has one meaning each
(0 match, 1 differ, 2 not compared, 3 compared but the difference image not written)."""
import os
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib

BELTSIM = None
SANITIZED = False  # AddressSanitizer maps terabytes of shadow memory: no address-space limit then

# The address space the program may take: a few times what it maps to compare two small files
# (it needs 256-384 MB of address space for its libraries alone, measured with RLIMIT_AS) and far
# below the 4.8 GB that a 40000x40000 RGB image takes.
ADDRESS_SPACE = 1 << 30


def limited():
    if not SANITIZED:
        resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def run(args, cwd, timeout=60):
    """the exit status, stdout and stderr; a hang past `timeout` raises (the FIFO's test failure)"""
    # stdin closed: a command that reads it (the console) must not wait on or take ctest's
    p = subprocess.run([BELTSIM] + args, capture_output=True, text=True, cwd=cwd, timeout=timeout,
                       stdin=subprocess.DEVNULL, preexec_fn=limited)
    return p.returncode, p.stdout, p.stderr


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png_bytes(width, height, raw):
    """an 8-bit RGB PNG whose header says width x height, with `raw` (compressed) as its data"""
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def grey(width, height):
    return png_bytes(width, height, b"".join(b"\0" + b"\x80" * (3 * width) for _ in range(height)))


class Base(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_hostile_")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def path(self, name):
        return os.path.join(self.dir, name)

    def write(self, name, data):
        with open(self.path(name), "wb" if isinstance(data, bytes) else "w") as f:
            f.write(data)
        return name


class Pngs(Base):
    def test_a_header_claiming_more_than_the_file_holds_is_refused_before_allocating(self):
        self.write("b.png", grey(8, 8))
        for side, reason in [(40000, "exceeds user limit"), (1000000, "exceeds user limit"),
                             (15000, "its header claims 15000x15000 pixels, more than the 100000000 beltsim reads"),
                             (9000, "its header claims 9000x9000 pixels (243009000 bytes of rows), more than its "
                                    "68 bytes can hold (deflate packs at most 1032 bytes into one)")]:
            name = self.write("big.png", png_bytes(side, side, b"\0" * 10))
            self.assertEqual(os.path.getsize(self.path(name)), 68)
            code, out, err = run(["compare", name, "b.png"], self.dir)
            self.assertEqual((code, out), (2, ""), err)
            self.assertIn("read_png big.png: ", err)
            self.assertIn(reason, err)

    def test_a_png_past_the_size_limit_is_refused_by_its_header(self):
        # well compressed (zeros), so that its bytes could hold it: the limit on the sides refuses it
        name = self.write("wide.png", png_bytes(30000, 2, b"\0" * (2 * (1 + 3 * 30000))))
        code, out, err = run(["compare", name, name], self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("wide.png", err)
        self.assertIn("exceeds user limit", err)
        self.assertIn("at most 20000 pixels a side", err)

    def test_a_fifo_or_a_device_is_not_read(self):
        self.write("b.png", grey(8, 8))
        os.mkfifo(self.path("fifo.png"))
        for name in ("fifo.png", "/dev/zero"):
            code, out, err = run(["compare", name, "b.png"], self.dir, timeout=30)
            self.assertEqual((code, out), (2, ""), err)
            self.assertIn("cannot read " + name + ": ", err)
            self.assertIn("not a regular file", err)

    def test_a_match_whose_difference_image_cannot_be_written_exits_3(self):
        self.write("a.png", grey(8, 8))
        shutil.copy(self.path("a.png"), self.path("b.png"))
        # (a missing folder is made, as every output's: a file stands where its folder would be)
        code, out, err = run(["compare", "a.png", "b.png", "--diff", "b.png/d.png"], self.dir)
        self.assertEqual(code, 3, out + err)
        self.assertTrue(out.startswith("match: "), out)
        self.assertIn("b.png/d.png", err)
        # and one that differs: still 3, the line says so
        self.write("c.png", png_bytes(8, 8, b"".join(b"\0" + b"\xff" * 24 for _ in range(8))))
        code, out, err = run(["compare", "a.png", "c.png", "--diff", "b.png/d.png"], self.dir)
        self.assertEqual(code, 3, out + err)
        self.assertTrue(out.startswith("differ: "), out)


class Scripts(Base):
    def test_a_script_that_is_a_fifo_or_a_device_is_not_read(self):
        # `beltsim run fifo.lua` blocked in its open, deaf to SIGTERM (a user trial)
        os.mkfifo(self.path("fifo.lua"))
        for args in (["run", "fifo.lua"], ["run", "/dev/zero"], ["console", "fifo.lua"], ["wp", "fifo.lua"],
                     ["sweep", "fifo.lua", "--set", "x=1,2"]):
            code, out, err = run(args, self.dir, timeout=30)
            self.assertEqual(code, 1, err)
            self.assertIn("not a regular file", err)


class Csvs(Base):
    def test_a_fifo_is_not_read(self):
        self.write("a.csv", "t,x\n0,1\n")
        os.mkfifo(self.path("fifo.csv"))
        code, out, err = run(["compare", "a.csv", "fifo.csv"], self.dir, timeout=30)
        self.assertEqual((code, out), (2, ""), err)
        self.assertIn("cannot read fifo.csv: ", err)
        self.assertIn("not a regular file", err)
        code, out, err = run(["plot", "fifo.csv", "--out", "p.png"], self.dir, timeout=30)
        self.assertEqual(code, 1, err)
        self.assertIn("cannot read fifo.csv: ", err)

    def test_many_columns_take_time_linear_in_them(self):
        # 200 000 columns: read and compared in about a second (measured 0.8 s of CPU); a quadratic
        # reading (each name looked up among those before it, 2e10 comparisons) takes minutes,
        # far past the timeout
        n = 200000
        header = "t," + ",".join("c%d" % i for i in range(n))
        row = lambda t: repr(t) + "," + ",".join("1" for _ in range(n))
        self.write("wide.csv", header + "\n" + row(0.0) + "\n" + row(0.1) + "\n")
        code, out, err = run(["compare", "wide.csv", "wide.csv"], self.dir, timeout=60)
        self.assertEqual(code, 0, err)
        self.assertEqual(out, "match: %d columns agree at 2 times: every value equal\n" % n)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    with open(BELTSIM, "rb") as f:
        SANITIZED = b"__asan_init" in f.read()
    unittest.main()
