-- The paper's two pulleys on fixed centres, the belt's tension at rest from its length alone (no
-- tensioner): a kinematic driver brought to w rad/s by 0.1 s, the driven pulley nearly unloaded
-- (M N·m at speed), the contact and the bending damping per length (docs/model.md, element count:
-- the running tension against the element count; docs/summary.md: the hub load at speed). Used by
--   beltsim run scripts/fixed_centres.lua --no-frames --set w=100 --set n=120 --out out/fc_n120
--   beltsim summary out/fc_n120 --from 0.2
-- Parameters (--set KEY=VALUE): w  the driver's speed [rad/s] (default 300: 30 m/s of belt),
-- n  element count (default 120), M  the driven pulley's load at w [N·m] (default 1), t_end [s].
-- SI units; counter-clockwise positive.

local a = beltsim.args
local w, n, M = a.w or 300, a.n or 120, a.M or 1
local route = 2 * 0.29 + 2 * math.pi * 0.1      -- m, the pitch line round the two pulleys
local pitch60 = route / 60                       -- m, the paper's element pitch
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0, 0}, radius = 0.1, speed = beltsim.ramp{ t1 = 0.1, to = -w, shape = "cosine" } },
    { name = "driven", centre = {0.29, 0}, radius = 0.1, inertia = 0.025, torque = { per_speed = -M / w } },
  },
  belt = { elements = n, pretension = 500, direction = "cw", mu = 1, bending_viscosity = 1e-6 },
  contact = { c1_per_length = 3.0256e9 / pitch60, c2_per_length = 6.5e5 / pitch60,
              damping_per_length = 300 / pitch60, p_max = 1e-3 },
  gravity = 0,
  energy = true,
}
drive:run { t_end = a.t_end or 0.3, sample = 5e-4 }
