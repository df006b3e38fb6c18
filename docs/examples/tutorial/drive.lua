-- The tutorial's drive (docs/tutorial.md): a crankshaft drives an alternator through a
-- poly-V belt; an idler on the belt's back side makes the alternator's wrap longer.
--   beltsim run docs/examples/tutorial/drive.lua                      0.3 s, frames and a video
--   beltsim console docs/examples/tutorial/drive.lua --set live=true  `sim` at t = 0, at a prompt

drive = beltsim.scene {
  pulleys = {
    { name = "crankshaft", centre = {0.0, 0.0}, radius = 0.075, inertia = 0.02,
      speed = beltsim.ramp{ t1 = 0.1, to = -beltsim.rpm(800), shape = "cosine" } },  -- clockwise
    { name = "alternator", centre = {0.05, 0.25}, radius = 0.028, inertia = 2e-3,
      torque = { per_speed = -0.01 } },                          -- -2.5 N·m at 250 rad/s
    { name = "idler", centre = {0.04, 0.125}, radius = 0.035, inertia = 5e-5, wrap = "back" },
  },
  belt = { preset = "6PK", elements = 200, pretension = 300, direction = "cw" },
}

if beltsim.args.live then
  sim = drive:start { progress = false }
else
  local result = drive:run {
    t_end = 0.3,
    frames = { size = {640, 360}, quantity = "tension", range = {200, 350},
               png = true, png_every = 15, video = true },
  }
  print(string.format("t = %.2f s: crankshaft %.1f, alternator %.1f, idler %.1f rad/s",
                      result.t, result.omega.crankshaft, result.omega.alternator, result.omega.idler))
end
