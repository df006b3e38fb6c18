-- The sweep tests' drive (grid.lua, bad_point.lua, plain.lua and sweep_test.py's sweeps, which
-- `require "drive"`), defined here once: the paper's two pulleys with a 40-element belt, the driver
-- ramped to -20 N·m in 0.01 s against the driven pulley's -0.5 N·m·s/rad. drive(o) is the scene's
-- table, for beltsim.scene (an error in it then names the line of that call): o.pretension [N]
-- (500), o.mu (1), o.torque (the driver's), o.per_speed [N·m·s/rad] (the driven pulley's),
-- o.mass_per_length [kg/m] (the default when nil).
return function(o)
  return {
    pulleys = {
      { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025, torque = o.torque or beltsim.ramp(0.01, -20.0) },
      { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025, torque = { per_speed = o.per_speed or -0.5 } },
    },
    belt = { elements = 40, pretension = o.pretension or 500, mu = o.mu or 1, mass_per_length = o.mass_per_length },
  }
end
