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
# after the page's commands, the wet elements on the alternator's wrap at their end, which its
# text counts (it once said "8 of its 21 elements are wet, the rest not yet" of the wet stretch's
# tail leaving the wrap)
count = ("local w = {} for _, i in ipairs(sim:elements{ pulley = 'alternator' }) do if sim:element(i).mu < 1 then "
         "w[#w + 1] = i end end print('wet on the alternator: ' .. table.concat(w, ',') .. ' of ' .. "
         "#sim:elements{ pulley = 'alternator' })")
with tempfile.TemporaryDirectory() as out:
    console = subprocess.run([beltsim, "console", str(script_path), "--set", "live=true", "--out", out],
                             input="\n".join(commands + [count]) + "\n", capture_output=True, text=True,
                             timeout=240)
    if console.returncode != 0:
        failures.append("the tutorial's console commands exit %d:\n%s\n%s" %
                        (console.returncode, console.stdout[-3000:], console.stderr[-3000:]))
# what sim:wet says, as the page shows it; the wet elements on the wrap, as its text says
for line in page.splitlines():
    if line.startswith('"wet: ') and line not in console.stdout:
        failures.append("the page shows sim:wet saying %s; the console printed:\n%s" % (line, console.stdout[-3000:]))
said = re.search(r"(\d+) of its (\d+) elements are wet, the last of the wet stretch \(elements\s+(\d+) to (\d+)\)", page)
if not said:
    failures.append("docs/tutorial.md no longer says how many of the alternator's elements are wet at t = 0.1 s")
else:
    wet, on, first, last = (int(g) for g in said.groups())
    expect = "wet on the alternator: %s of %d" % (",".join(str(i) for i in range(first, last + 1)), on)
    if wet != last - first + 1 or expect not in console.stdout:
        failures.append("docs/tutorial.md says %s; the console printed:\n%s" % (said.group(0), console.stdout[-500:]))

for f in failures:
    print("FAIL:", f)
print("%d Lua blocks, %d console commands checked" % (len(blocks), len(commands)))
sys.exit(1 if failures else 0)
