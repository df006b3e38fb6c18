#!/usr/bin/env python3
"""docs/tutorial.md against the program: every Lua block of the page is text of the tutorial's
script, and the console commands the page shows (its lines starting "> ") run without an error
when piped into `beltsim console` on that script (the console exits 1 if any command failed).

usage: tutorial_test.py BELTSIM SOURCE_DIR"""
import pathlib
import re
import subprocess
import sys
import tempfile

beltsim, source = sys.argv[1], pathlib.Path(sys.argv[2])
page = (source / "docs/tutorial.md").read_text()
script_path = source / "docs/examples/tutorial/drive.lua"
script = script_path.read_text()

failures = []
blocks = re.findall(r"```lua\n(.*?)```", page, re.S)
if not blocks:
    failures.append("docs/tutorial.md has no ```lua block")
for block in blocks:
    if block not in script:
        failures.append("a Lua block of docs/tutorial.md is not in %s:\n%s" % (script_path, block))

commands = [line[2:] for line in page.splitlines() if line.startswith("> ")]
if not commands:
    failures.append("docs/tutorial.md shows no console command (lines starting '> ')")
with tempfile.TemporaryDirectory() as out:
    console = subprocess.run([beltsim, "console", str(script_path), "--set", "live=true", "--out", out],
                             input="\n".join(commands) + "\n", capture_output=True, text=True, timeout=240)
    if console.returncode != 0:
        failures.append("the tutorial's console commands exit %d:\n%s\n%s" %
                        (console.returncode, console.stdout[-3000:], console.stderr[-3000:]))

for f in failures:
    print("FAIL:", f)
print("%d Lua blocks, %d console commands checked" % (len(blocks), len(commands)))
sys.exit(1 if failures else 0)
