-- A crankshaft driving a generator on a 6PK belt: the crankshaft's speed ramps to 120 rad/s in
-- 0.05 s, the generator (r = 0.05 m) carries a load of 0.04 N·m per rad/s. On so few elements
-- the span tensions ripple by several per cent as the elements pass the pulleys (the slack span
-- ±28 N at 60 elements), a scene whose span tensions at an instant keep the accuracy contract
-- only with the belt divided finely, used by the accuracy matrix (docs/accuracy.md).
--   beltsim run scripts/crank_generator.lua --set elements=100     element count (default 60)
-- SI units; counter-clockwise positive.

local elements = beltsim.args.elements or 60
local drive = beltsim.scene {
  pulleys = {
    { name = "crank", centre = {0, 0}, radius = 0.08, inertia = 0.02,
      speed = beltsim.ramp{ t1 = 0.05, to = -120, shape = "cosine" } },
    { name = "gen", centre = {0.30, 0}, radius = 0.05, inertia = 2e-3, torque = { per_speed = -0.04 } },
  },
  belt = { preset = "6PK", elements = elements, pretension = 400, direction = "cw" },
}
local r = drive:run { t_end = 0.1 }
print(string.format("%d elements, t = %.3f s: crank %.3f, gen %.3f rad/s", elements, r.t, r.omega.crank, r.omega.gen))
