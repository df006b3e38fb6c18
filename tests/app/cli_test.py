#!/usr/bin/env python3
"""`--set KEY=VALUE` on the command line: beltsim.args in run, console and wp, the checks of the
values (exit 2), and a key the script never read (exit 1 naming it, with a suggestion)."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

BELTSIM = None


def run(args, stdin=None, cwd=None):
    p = subprocess.run([BELTSIM] + args, input=stdin, capture_output=True, text=True, cwd=cwd, timeout=120)
    return p.returncode, p.stdout, p.stderr


class SetOption(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_cli_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.script = os.path.join(self.dir, "args.lua")
        with open(self.script, "w") as f:
            f.write("local a = beltsim.args\n"
                    "print(a.elements, math.type(a.elements), a.mu, a.wet, a.name)\n")

    def test_values_reach_the_script(self):
        code, out, err = run(["run", self.script, "--set", "elements=120", "--set", "mu=0.3",
                              "--set", "wet=true", "--set", "name=esdirk32"], cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertEqual(out.split(), ["120", "integer", "0.3", "true", "esdirk32"])

    def test_unread_key_is_an_error_naming_it(self):
        code, out, err = run(["run", self.script, "--set", "elemnts=120"], cwd=self.dir)
        self.assertEqual(code, 1, err)
        self.assertIn("--set elemnts=120 was never read by " + self.script + " (did you mean 'elements'?); "
                      "keys it read: elements, mu, wet, name", err)

    def test_values_that_start_like_numbers_must_be_numbers(self):
        for value in ["0x10", "1e", "-inf", "+nan", "2s", ".5.5"]:
            code, out, err = run(["run", self.script, "--set", "elements=" + value], cwd=self.dir)
            self.assertEqual(code, 2, value + ": " + err)
            self.assertIn("--set elements=" + value + ": a value that starts like a number", err)
        code, out, err = run(["run", self.script, "--set", "elements=1", "--set", "elements=2"], cwd=self.dir)
        self.assertEqual(code, 2, err)
        self.assertIn("elements is set twice", err)

    def test_console_and_a_command_that_takes_none(self):
        code, out, err = run(["console", self.script, "--set", "elements=48"], stdin="print(beltsim.args.elements * 2)\n",
                             cwd=self.dir)
        self.assertEqual(code, 0, err)
        self.assertIn("96", out)
        code, out, err = run(["plot", os.path.join(self.dir, "x.csv"), "--set", "a=1"], cwd=self.dir)
        self.assertEqual(code, 2, err)


if __name__ == "__main__":
    BELTSIM = sys.argv.pop(1)
    unittest.main(verbosity=2)
