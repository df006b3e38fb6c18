-- A user's scenario guarded by a golden test (docs/testing-your-scenario.md): the paper's
-- two-pulley drive, coarse (40 elements) and short (0.05 s) so its test takes a second or two.
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0, 0},    radius = 0.1, inertia = 0.025, torque = beltsim.ramp(0.3, -70) },
    { name = "driven", centre = {0.29, 0}, radius = 0.1, inertia = 0.025, torque = { per_speed = -0.955 } },
  },
  belt = { elements = 40, pretension = 500, direction = "cw" },
}

drive:run {
  t_end = 0.05,
  sample = 1e-3,
  rtol = 1e-5,
  progress = false,
  -- one picture at the end (frame 15 of 0.05 s at 300 frames per simulated second)
  frames = { fps = 30, slowdown = 10, size = {320, 180}, quantity = "tension", range = {0, 1000},
             png = true, png_every = 15, video = false },
}
