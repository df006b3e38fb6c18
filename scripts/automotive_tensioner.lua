-- The automotive drive of Kubas §4 (the layout of automotive_wet.lua, dry) with its idler on a
-- spring-loaded tensioner arm, the crankshaft driven at 800 rpm with the firing pulsation of a
-- four-cylinder four-stroke engine: its second order, ±4 rad/s twice a revolution (26.7 Hz).
-- The spring's free angle holds the belt's 280 N at rest (scene.hpp, TensionerDef). The belt is
-- a 6PK (its preset, docs/belts.md); --set belt=paper takes the paper's defaults instead, whose
-- bending dampers take more power than the accessories (the run's first lines warn).
--   beltsim run scripts/automotive_tensioner.lua                      the idler on its arm
--   beltsim run scripts/automotive_tensioner.lua --set idler=fixed    the same idler held fixed
--   beltsim run scripts/automotive_tensioner.lua --set belt=paper     the paper's belt
--   beltsim run scripts/automotive_tensioner.lua --set elements=386   a finer belt (default 150),
--     its contact constants per length, equal to the defaults' at 150 elements (docs/model.md,
--     element count: what the tensioner's 51° wrap gains from it)
-- docs/automotive.md compares the first two: the arm's angle and the span tensions.

local fixed = beltsim.args.idler == "fixed"
local paper = beltsim.args.belt == "paper"
assert(paper or beltsim.args.belt == nil, "--set belt=paper or no belt key, got " .. tostring(beltsim.args.belt))
local crank_speed = -beltsim.rpm(800)  -- clockwise, with the belt

local idler = { name = "tensioner", centre = {0.015, -0.12}, radius = 0.031, inertia = 5e-5, wrap = "back" }
if not fixed then
  -- arm 63 mm from the pivot; an automotive tensioner's spring (30 N·m/rad), a light viscous
  -- damper and 0.5 N·m of pivot friction, three times harder when the belt pushes the arm back
  idler.tensioner = { pivot = {0.075, -0.14}, inertia = 1e-3, stiffness = 30,
                      damping = 0.05, friction_torque = 0.5, asymmetric = 3 }
end

local elements = beltsim.args.elements or 150
local function build(contact)
  return beltsim.scene {
    pulleys = {
      { name = "crankshaft", centre = {0.09, -0.27}, radius = 0.080, inertia = 0.02,
        speed = { beltsim.ramp{ t1 = 0.2, to = crank_speed, shape = "cosine" },
                  { mean_speed = -crank_speed, harmonics = {{2, 4.0, 0}} } } },
      idler,
      { name = "alternator", centre = {0.0, 0.0}, radius = 0.027, inertia = 2e-3,
        torque = { per_speed = -0.01 } },          -- 2.5 N·m at 250 rad/s
      { name = "pump", centre = {0.16, -0.06}, radius = 0.056, inertia = 1e-3,
        torque = { per_speed = -0.05 } },          -- 6 N·m at 120 rad/s
    },
    belt = { preset = not paper and "6PK" or nil, elements = contact and elements or 150, pretension = 280,
             direction = "cw" },
    contact = contact,
    energy = true,
  }
end
-- the default contact (contact.c1, c2, damping per element, `beltsim help parameters`) at 150
-- elements, given per metre so that refining keeps it: l the pitch of 150 on the route's 1.0565 m
-- (parameters.csv's route.length)
local l = 1.0564652402479746 / 150
local drive = build(elements ~= 150 and { c1_per_length = 3.0256e9 / l, c2_per_length = 6.5e5 / l,
                                         damping_per_length = 300 / l } or nil)

local result = drive:run { t_end = 0.6, sample = 5e-4 }
print(string.format("t = %.3f s (%s idler): crankshaft %.2f, alternator %.2f, pump %.2f rad/s",
  result.t, fixed and "fixed" or "arm", result.omega.crankshaft, result.omega.alternator, result.omega.pump))
