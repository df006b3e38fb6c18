"""The test scenes in Lua for the Python tests: the scene of tests/support/two_pulley.lua, which the
C++ tests read too (support/scenes.hpp).

two_pulley: that scene, its value in a local `drive`. The text starts with an empty line and has 8
lines: a script's next line is line 9, which the tests' expected messages name."""

import os
import re

_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "two_pulley.lua")


def _text():
    with open(_FILE) as f:
        text = f.read()
    at = text.find("local s = ")
    if at < 0:
        raise SystemExit("%s: no line 'local s = '" % _FILE)
    return text[at:]


def two_pulley(elements=None, inertia=None):
    """elements: the belt's (the file's when None); inertia [kg·m²]: both pulleys' (the scene's
    default when None)"""
    s = "\n" + _text().replace("local s = ", "local drive = ", 1)
    if elements is not None:
        s, n = re.subn(r"elements = [0-9]+", "elements = %d" % elements, s, count=1)
        assert n == 1, _FILE
    if inertia is not None:
        s, n = re.subn(r"(name = '\w+', centre = \{[^}]*\}, radius = [^,]*, )", r"\1inertia = %r, " % inertia, s)
        assert n == 2, _FILE
    return s
