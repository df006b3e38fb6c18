-- Cost of a drive in the per-length form (scripts/refine_dry.lua's "per length": contact and
-- bending damping given per metre, equal to the paper's at its element pitch) over one window, by
-- element count: steps, rejected steps, Jacobians and wall time of the window, and the pulley
-- speeds at its end (to compare answers). Parameters (--set KEY=VALUE):
--   drive "dry" (the paper's two-pulley drive, default), "wet" (the same with half the belt at
--         mu 0.2, as scripts/paper_wet.lua) or "automotive" (scripts/automotive_wet.lua's four
--         pulleys, 30 % wet; the paper's values per metre at its 150-element pitch)
--   n     element count (default 60)
--   t0    window start [s] (default 0.5), reached at the same rtol
--   t1    window end [s] (default 0.55)
--   rtol  relative tolerance (default 1e-3)
-- e.g. beltsim run scripts/fine_belt_window.lua --no-frames --set n=600
-- SI units; counter-clockwise positive.

local a = beltsim.args
local n, t0, t1, rtol = a.n or 60, a.t0 or 0.5, a.t1 or 0.55, a.rtol or 1e-3

local kind = a.drive or "dry"
local function per_length(pitch)
  return { c1_per_length = 3.0256e9 / pitch, c2_per_length = 6.5e5 / pitch,
           damping_per_length = 300 / pitch, p_max = 1e-3 }
end
local scene
if kind == "dry" or kind == "wet" then
  local route = 2 * 0.29 + 2 * math.pi * 0.1      -- m, the pitch line round the two pulleys
  local pitch60 = route / 60                       -- m, the paper's element pitch
  local mu = 1.0
  if kind == "wet" then mu = function(site) if site.x > 0.29 / 2 then return 0.2 else return 1.0 end end end
  scene = beltsim.scene {
    pulleys = {
      { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025, torque = beltsim.ramp(0.3, -70.0) },
      { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025,
        torque = { per_speed = -70.0 / beltsim.rpm(700) } },
    },
    belt = {
      elements = n, pretension = 500, direction = "cw", EA = 1.52e5, EI = 0.026, axial_damping = 20.5,
      mass_per_length = 0.096, mu = mu, bending_viscosity = 0.05 * pitch60,
    },
    contact = per_length(pitch60),
    friction = { dv = 1e-5 }, gravity = 9.81,
  }
elseif kind == "automotive" then
  local pulleys = {
    { name = "crankshaft", centre = {0.09, -0.27}, radius = 0.080, inertia = 0.02,
      torque = beltsim.ramp(0.3, -70.0) },
    { name = "tensioner", centre = {0.015, -0.12}, radius = 0.031, inertia = 5e-5, wrap = "back" },
    { name = "alternator", centre = {0.0, 0.0}, radius = 0.027, inertia = 2e-3 },
    { name = "pump", centre = {0.16, -0.06}, radius = 0.056, inertia = 1e-3,
      torque = { per_speed = -70.0 / beltsim.rpm(700) } },
  }
  local wet = function(site)
    local behind = (site.leaves.pump - site.s) % site.length
    if behind < 0.3 * site.length then return 0.2 else return 1.0 end
  end
  local route = beltsim.scene { pulleys = pulleys, belt = { elements = 150, pretension = 280, direction = "cw" } }
  local pitch150 = route:info().route_length / 150
  scene = beltsim.scene {
    pulleys = pulleys,
    belt = { elements = n, pretension = 280, direction = "cw", mu = wet, bending_viscosity = 0.05 * pitch150 },
    contact = per_length(pitch150),
  }
else
  error("drive must be dry, wet or automotive, not " .. tostring(kind))
end

local sim = scene:start { rtol = rtol, sample = 1e-3, progress = false }
local before = sim:run_to(t0)
local s0 = sim:stats()
local w = sim:run_to(t1)
local s1 = sim:stats()
print(string.format(
  "%s elements %d rtol %g window %g-%g s: steps %d rejected %d jacobians %d wall %.3f s | prefix steps %d wall %.2f s" ..
    " | driver %.6f driven %.6f rad/s",
  kind, n, rtol, t0, t1, w.steps, s1.rejected - s0.rejected, s1.jacobians - s0.jacobians, w.wall, before.steps,
  before.wall, sim:pulley(kind == "automotive" and "crankshaft" or "driver").omega,
  sim:pulley(kind == "automotive" and "pump" or "driven").omega))
sim:close()
