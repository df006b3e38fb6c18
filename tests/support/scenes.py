"""The test scenes in Lua for the Python tests, as support/scenes.hpp holds them for the C++ ones.

two_pulley: the paper's two-pulley drive (scripts/paper_dry.lua's geometry: two pulleys of 0.1 m,
0.29 m apart, the belt at 500 N turning clockwise), its value in a local `drive`. The text starts
with an empty line and has 8 lines: a script's next line is line 9, which the tests' expected
messages name."""


def two_pulley(elements=40, inertia=None):
    """inertia [kg·m²]: both pulleys' (the scene's default when None)"""
    i = "" if inertia is None else " inertia = %r," % inertia
    return ("\n"
            "local drive = beltsim.scene {\n"
            "  pulleys = {\n"
            "    { name = \"driver\", centre = {0, 0},    radius = 0.1,%s torque = beltsim.ramp(0.3, -70) },\n"
            "    { name = \"driven\", centre = {0.29, 0}, radius = 0.1,%s torque = { per_speed = -0.955 } },\n"
            "  },\n"
            "  belt = { elements = %d, pretension = 500, direction = \"cw\" },\n"
            "}\n" % (i, i, elements))
