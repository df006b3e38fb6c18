-- The paper's two-pulley drive with half of the belt wet (Kubas, §3, Figs 14–18).
-- μ = 0.2 on the half of the belt whose elements start on the driven side (x > l_p/2), μ = 1
-- elsewhere; the same torques as the dry case. The wet part travels with the belt.
--   beltsim run scripts/paper_wet.lua                          the paper's friction law (Threlfall's)
--   beltsim run scripts/paper_wet.lua --set friction=stribeck  Stribeck's, its parameters' defaults
--   beltsim run scripts/paper_wet.lua --set friction=lugre     LuGre's, its parameters' defaults
--                                                              (docs/friction.md)

local l_p = 0.29
local law = beltsim.args.friction  -- nil: the scene's default law, the paper's

local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025,
      torque = beltsim.ramp(0.3, -70.0) },
    { name = "driven", centre = {l_p, 0.0}, radius = 0.1, inertia = 0.025,
      torque = { per_speed = -70.0 / beltsim.rpm(700) } },
  },
  belt = {
    elements = 60,
    pretension = 500,
    direction = "cw",
    -- wet where the element starts on the driven pulley's half
    mu = function(site) if site.x > l_p / 2 then return 0.2 else return 1.0 end end,
  },
  friction = law and { law = law } or nil,
  energy = true,
}

-- the selected element sits in the middle of the wet part: the outer side of the driven pulley
local result = drive:run {
  t_end = 1.0,
  sample = 1e-3,
  probe = {l_p + 0.1, 0.0},
  -- the friction force each element feels (along the travel: positive where the pulley drives
  -- the belt) shows where the belt grips; the wet half is marked blue along its back, the
  -- elements that slip magenta along their inside
  frames = {
    fps = 30, slowdown = 10, size = {1280, 720},
    quantity = "friction", range = {-100, 100},
    magnify = 10,
    png = true, png_every = 30,
    video = "paper_wet.mp4",
  },
}
print(string.format("t = %.3f s: driver %.3f rad/s, driven %.3f rad/s",
  result.t, result.omega.driver, result.omega.driven))
if result.frames > 0 then
  print(string.format("%d frames: %s/frames/ (PNG, every 30th) and %s/paper_wet.mp4",
    result.frames, result.csv:match("(.*)/"), result.csv:match("(.*)/")))
end
