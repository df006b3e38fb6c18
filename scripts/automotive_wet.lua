-- The automotive drive of Kubas §4 (Figs 19–23): crankshaft, tensioner idler (on the belt's back),
-- alternator and coolant pump; 150 elements, 280 N, 30 % of the belt wet.
-- The layout (Fig. 19 has no coordinates) and the inertias are ours (docs/model.md, Our choices): origin at the
-- alternator, belt travelling clockwise, pulleys listed in the order the belt visits them.
-- The belt is the paper's, to reproduce its figures (docs/paper.md): its bending dampers take a
-- large share of the power on these small pulleys, and the run's first lines warn so (a PK belt's
-- own: docs/belts.md).

local drive = beltsim.scene {
  pulleys = {
    { name = "crankshaft", centre = {0.09, -0.27}, radius = 0.080, inertia = 0.02,
      torque = beltsim.ramp(0.3, -70.0) },                                -- Fig. 7a, clockwise
    { name = "tensioner", centre = {0.015, -0.12}, radius = 0.031, inertia = 5e-5, wrap = "back" },
    { name = "alternator", centre = {0.0, 0.0}, radius = 0.027, inertia = 2e-3 },
    { name = "pump", centre = {0.16, -0.06}, radius = 0.056, inertia = 1e-3,
      torque = { per_speed = -70.0 / beltsim.rpm(700) } },               -- Fig. 7b
  },
  belt = {
    elements = 150,
    pretension = 280,
    direction = "cw",
    -- wet: the 30 % of the belt whose leading end is where the belt leaves the pump
    mu = function(site)
      local behind = (site.leaves.pump - site.s) % site.length
      if behind < 0.3 * site.length then return 0.2 else return 1.0 end
    end,
  },
  energy = true,
}

local info = drive:info()
print(string.format("route %.4f m; wraps: crankshaft %.0f°, tensioner %.0f°, alternator %.0f°, pump %.0f°",
  info.route_length, info.wrap_deg.crankshaft, info.wrap_deg.tensioner, info.wrap_deg.alternator,
  info.wrap_deg.pump))

-- the selected element: in the wet part, on the pump at the start (paper Fig. 19)
local result = drive:run {
  t_end = 1.0,
  sample = 1e-3,
  probe = {0.16 + 0.056, -0.06},
  -- slip velocity against each pulley: the wet part slipping on the pump, then on the
  -- crankshaft; a 10 s clip ten times slower than life, a PNG every 0.1 s
  frames = {
    fps = 30, slowdown = 10, size = {1280, 720},
    quantity = "slip", range = {-2, 2},
    magnify = 2,
    png = true, png_every = 30,
    video = "automotive_wet.mp4",
  },
}
print(string.format("t = %.3f s: crankshaft %.2f, alternator %.2f, pump %.2f, tensioner %.2f rad/s",
  result.t, result.omega.crankshaft, result.omega.alternator, result.omega.pump, result.omega.tensioner))
if result.frames > 0 then
  print(string.format("%d frames: %s/frames/ (PNG, every 30th) and %s/automotive_wet.mp4",
    result.frames, result.csv:match("(.*)/"), result.csv:match("(.*)/")))
end
