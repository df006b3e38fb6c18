-- The paper's dry drive as a live simulation, for the console:
--   beltsim console scripts/live_dry.lua
-- then, at the prompt: sim:run_to(0.3), sim:pulley("driver"), sim:wet{from = 0, to = 0.3, mu = 0.2},
-- sim:show{quantity = "slip"}, sim:advance(0.2), sim:plot{"driver.omega", "driven.omega"}.
-- SI units; counter-clockwise positive; the pulley inertias are ours (docs/model.md).

drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025,
      torque = beltsim.ramp(0.3, -70.0) },                                 -- Fig. 7a
    { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025,
      torque = { per_speed = -70.0 / beltsim.rpm(700) } },                 -- Fig. 7b
  },
  belt = {
    elements = 60, pretension = 500, direction = "cw",
    EA = 1.52e5, EI = 0.026, axial_damping = 20.5, bending_damping = 0.05,  -- read as in docs/model.md
    mass_per_length = 0.096, mu = 1.0,
  },
  energy = true,
}

-- the paper's selected element starts where the upper span meets the driven pulley
sim = drive:start { probe = {0.29, 0.1} }
print(string.format("sim: the dry drive at t = %g s; outputs in %s", sim.t, sim:stats().out))
