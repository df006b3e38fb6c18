-- The paper's dry second in the per-length form (contact constants per metre of belt and the
-- bending damping as a viscosity, equal to the paper's values at its 60-element pitch: the form whose
-- answers converge as the belt is divided, docs/model.md), at any element count. Used by
--   beltsim wp scripts/per_length_dry.lua --set n=240 --integrators esdirk32,cvode
-- Parameters (--set KEY=VALUE): n  element count (default 240).
-- SI units; counter-clockwise positive.

local n = beltsim.args.n or 240
local route = 2 * 0.29 + 2 * math.pi * 0.1      -- m, the pitch line round the two pulleys
local pitch60 = route / 60                       -- m, the paper's element pitch
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025, torque = beltsim.ramp(0.3, -70.0) },
    { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025,
      torque = { per_speed = -70.0 / beltsim.rpm(700) } },
  },
  belt = {
    elements = n, pretension = 500, direction = "cw", EA = 1.52e5, EI = 0.026, axial_damping = 20.5,
    mass_per_length = 0.096, mu = 1.0, bending_viscosity = 0.05 * pitch60,
  },
  contact = {
    c1_per_length = 3.0256e9 / pitch60, c2_per_length = 6.5e5 / pitch60,
    damping_per_length = 300 / pitch60, p_max = 1e-3,
  },
  friction = { dv = 1e-5 }, gravity = 9.81,
}
local r = drive:run { t_end = 1.0, sample = 1e-3 }
print(string.format("%d elements, t = %.3f s: driver %.4f, driven %.4f rad/s; %d steps, %.1f s", n, r.t,
  r.omega.driver, r.omega.driven, r.steps, r.wall))
