-- The test scene of the C++ and the Python tests (support/scenes.hpp, support/scenes.py), defined
-- here once: the paper's two-pulley drive (scripts/paper_dry.lua's geometry: two pulleys of 0.1 m,
-- 0.29 m apart, the belt at 500 N turning clockwise; the paper's belt, contact and friction, which
-- are the scene's defaults, and the default inertias), coarse. The tests take the lines from
-- `local s` on and replace the pieces a test varies (the assignment, each pulley's keys after
-- its name and centre, the number of elements, more keys of the belt and of the scene); a test's
-- expected line numbers count these 7 lines.
local s = beltsim.scene {
  pulleys = {
    { name = 'driver', centre = {0, 0}, radius = 0.1, torque = beltsim.ramp(0.3, -70) },
    { name = 'driven', centre = {0.29, 0}, radius = 0.1, torque = { per_speed = -0.955 } },
  },
  belt = { elements = 40, pretension = 500, direction = 'cw' },
}
