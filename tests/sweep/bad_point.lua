-- A sweep whose point mu = -1 fails (the scene refuses a negative friction coefficient) while
-- the other points run.
return beltsim.sweep {
  grid = { mu = {0.5, -1, 1.0} },
  run = function(p)
    local drive = beltsim.scene {
      pulleys = {
        { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025, torque = beltsim.ramp(0.01, -20.0) },
        { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025, torque = { per_speed = -0.5 } },
      },
      belt = { elements = 40, pretension = 500, mu = p.mu },
    }
    local r = drive:run { t_end = 0.02, sample = 1e-3, progress = false }
    return { slip = r.omega.driver - r.omega.driven }
  end,
}
