-- The paper's two-pulley drive, dry (μ = 1), with water sprayed on the slack span for a while:
-- a spray zone (docs/spray.md) on the upper span, the one leaving the driver, sprays from 0.4 s to
-- 0.5 s; the elements that pass it take μ = 0.2 and dry back over 2 m of travel. The wet stretch
-- (about 0.7 m of the 1.2 m belt) slips on the driven pulley and then on the driver, and the drive
-- grips again as the belt dries.
--   beltsim run scripts/spray_zone.lua

local l_p = 0.29

local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025,
      torque = beltsim.ramp(0.3, -70.0) },                                 -- Fig. 7a
    { name = "driven", centre = {l_p, 0.0}, radius = 0.1, inertia = 0.025,
      torque = { per_speed = -70.0 / beltsim.rpm(700) } },                 -- Fig. 7b
  },
  belt = { elements = 60, pretension = 500, direction = "cw", mu = 1.0 },
  -- the belt runs clockwise: the upper span leaves the driver (the slack side)
  spray = {
    { centre = {l_p / 2, 0.1}, radius = 0.03, mu = 0.2, from = 0.4, to = 0.5, drying_length = 2.0 },
  },
}

local sim = drive:start {
  sample = 1e-3,
  probe = {l_p / 2, 0.1},
  -- slip velocity against the pulleys; the wetted elements are marked blue along their back
  frames = {
    fps = 30, slowdown = 10, size = {1280, 720},
    quantity = "slip", range = {-2, 2},
    magnify = 2,
    png = true, png_every = 15,
    video = "spray_zone.mp4",
  },
}
-- how many elements the zone holds and how many dry, every 0.1 s
sim:every(0.1, function(s)
  local z = s:spray(1)
  print(string.format("t = %.1f s: driver %7.2f, driven %7.2f rad/s; zone %s, %d elements in it, %d drying",
    s.t, s:pulley("driver").omega, s:pulley("driven").omega, z.on and "on " or "off", z.inside, z.drying))
end)
sim:run_to(1.2)
sim:close()  -- says where the run ended, its steps, wall time and folder; the spray's on and off are in events.csv
