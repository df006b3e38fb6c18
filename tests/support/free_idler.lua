-- A free idler on a drive's tight side (tests/physics/known_answers_contact_test.cpp,
-- KnownAnswers.CreepSignOfEachPulley): the paper's two pulleys (scripts/paper_dry.lua) loaded to
-- 40 N·m, and a light idler of 0.05 m below them on the span that runs from the driven pulley onto
-- the driver, which carries no torque. The paper's belt, with a tenth of its bending damping (the
-- paper's 0.05 N·m·s/rad per SDE takes a fifth of the power on a pulley this small, and the
-- tension it loses there shows as a slip on the idler). Run it with
--   beltsim run tests/support/free_idler.lua --no-frames && beltsim summary out/free_idler --from 0.4
-- SI units; counter-clockwise positive.
local drive = beltsim.scene {
  pulleys = {
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025, torque = beltsim.ramp(0.3, -40.0) },
    { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025,
      torque = { per_speed = -40.0 / beltsim.rpm(700) } },
    { name = "idler", centre = {0.145, -0.22}, radius = 0.05, inertia = 1e-4 },
  },
  belt = { elements = 60, pretension = 500, direction = "cw", EA = 1.52e5, EI = 0.026, axial_damping = 20.5,
           bending_damping = 0.005, mass_per_length = 0.096, mu = 1.0 },
  contact = { c1 = 3.0256e9, c2 = 6.5e5, damping = 300, p_max = 1e-3 },
  friction = { dv = 1e-5 },
}
local r = drive:run { t_end = 0.6, sample = 1e-3 }
print(string.format("t = %.3f s: driver %.2f, driven %.2f, idler %.2f rad/s", r.t, r.omega.driver, r.omega.driven,
  r.omega.idler))
