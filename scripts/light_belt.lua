-- A light belt from a datasheet, with no bending damping, on two small pulleys: the driver's
-- speed ramps to 12 rad/s, the driven pulley carries a load torque of −2·ω and a 25 N·m ramp.
-- Nothing damps the elements' own rotation, so they ring at their bending frequencies while the
-- drive runs: a scene whose answer (pulley speeds, span tensions) does not depend on that ringing,
-- used by the accuracy matrix (docs/accuracy.md).
--   beltsim run scripts/light_belt.lua --set n=240     element count (default 60)
-- SI units; counter-clockwise positive.

local n = beltsim.args.n or 60
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 2e-3,
      speed = beltsim.ramp{ t1 = 0.5, to = -12.0, shape = "cosine" } },
    { name = "driven", centre = {0.314, 0.0}, radius = 0.1, inertia = 2e-3,
      torque = { { per_speed = -2.0 }, beltsim.ramp(0.5, 25.0) } },
  },
  belt = {
    elements = n, strain = 0.05, direction = "cw",
    EA = 8e3, EI = 1.33e-3, mass_per_length = 0.0083, bending_damping = 0,
    mu = 0.5,
  },
  contact = { c1_per_length = 0, c2_per_length = 3.2e8, damping_per_length = 6400, p_max = 1e-3 },
  gravity = 0,
}
local r = drive:run { t_end = 2.45, sample = 1e-3 }
print(string.format("%d elements, t = %.3f s: driver %.4f, driven %.4f rad/s; %d steps, %.1f s", n, r.t,
  r.omega.driver, r.omega.driven, r.steps, r.wall))
