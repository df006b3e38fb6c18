-- Two equal 60 mm pulleys 0.25 m apart on a 6PK belt (the preset's light bending damping), a
-- kinematic driver brought to 100 rad/s by 0.1 s, the driven pulley lightly loaded, no wetting:
-- a plain drive on which the span tensions miss the accuracy contract at rtol 1e-4 and 1e-5
-- without a warning (docs/accuracy.md, the accuracy contract). Used by
--   beltsim wp scripts/short_6pk.lua --integrators trbdf2 --rtols 1e-3,1e-4,1e-5
-- Parameters (--set KEY=VALUE): n element count (default 100), t_end [s] (default 0.15).
-- SI units; counter-clockwise positive.

local a = beltsim.args
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = { 0, 0 }, radius = 0.06, inertia = 0.02,
      speed = beltsim.ramp { t1 = 0.1, to = -100, shape = "cosine" } },
    { name = "driven", centre = { 0.25, 0 }, radius = 0.06, inertia = 2e-3, torque = { per_speed = -0.05 } },
  },
  belt = { preset = "6PK", elements = a.n or 100, pretension = 400, direction = "cw" },
}
drive:run { t_end = a.t_end or 0.15 }
