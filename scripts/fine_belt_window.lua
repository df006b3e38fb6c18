-- Cost of the per-length dry drive (scripts/refine_dry.lua's "per length" form) over one window,
-- by element count: steps, rejected steps, Jacobians and wall time of the window, and the pulley
-- speeds at its end (to compare answers). Parameters (--set KEY=VALUE):
--   n     element count (default 60)
--   t0    window start [s] (default 0.5), reached at the same rtol
--   t1    window end [s] (default 0.55)
--   rtol  relative tolerance (default 1e-3)
-- e.g. beltsim run scripts/fine_belt_window.lua --no-frames --set n=600
-- SI units; counter-clockwise positive.

local a = beltsim.args
local n, t0, t1, rtol = a.n or 60, a.t0 or 0.5, a.t1 or 0.55, a.rtol or 1e-3

local route = 2 * 0.29 + 2 * math.pi * 0.1      -- m, the pitch line round the two pulleys
local pitch60 = route / 60                       -- m, the paper's element pitch
local scene = beltsim.scene {
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

local sim = scene:start { rtol = rtol, sample = 1e-3, progress = false }
local before = sim:run_to(t0)
local s0 = sim:stats()
local w = sim:run_to(t1)
local s1 = sim:stats()
print(string.format(
  "elements %d rtol %g window %g-%g s: steps %d rejected %d jacobians %d wall %.3f s | prefix steps %d wall %.2f s" ..
    " | driver %.6f driven %.6f rad/s",
  n, rtol, t0, t1, w.steps, s1.rejected - s0.rejected, s1.jacobians - s0.jacobians, w.wall, before.steps,
  before.wall, sim:pulley("driver").omega, sim:pulley("driven").omega))
sim:close()
