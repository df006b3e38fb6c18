-- An ordinary script for the quick form: beltsim sweep plain.lua --set pretension=300,500 --set mu=0.3,1
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025, torque = beltsim.ramp(0.01, -20.0) },
    { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025, torque = { per_speed = -0.5 } },
  },
  belt = { elements = 40, pretension = beltsim.args.pretension or 500, mu = beltsim.args.mu or 1 },
}
drive:run { t_end = beltsim.args.t_end or 0.02, sample = 1e-3, progress = false }
