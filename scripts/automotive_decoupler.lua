-- The automotive drive of automotive_tensioner.lua (dry, the idler on its arm, the crankshaft at
-- 800 rpm with its second-order firing pulsation) with the alternator's rotor behind a decoupler:
-- the pulley (1e-4 kg·m²) drives the rotor (2e-3 kg·m²) through a soft torsional spring
-- (15 N·m/rad: the rotor on it alone rings at 13.8 Hz, half the 26.7 Hz pulsation) and, by
-- default, an overrunning clutch. At 0.4 s the crankshaft drops to 600 rpm within 30 ms (a gear
-- shift): the alternator pulley decelerates faster than its loaded rotor would, and the clutch
-- lets the rotor run on. The alternator's load (per_speed -0.01: 2.5 N·m at 250 rad/s) acts on
-- its rotor. The belt is a 6PK (its preset, docs/belts.md).
--   beltsim run scripts/automotive_decoupler.lua                          one-way decoupler
--   beltsim run scripts/automotive_decoupler.lua --set coupling=two_way   the spring alone
--   beltsim run scripts/automotive_decoupler.lua --set coupling=none      a solid alternator
-- docs/automotive.md plots the pulley's and the rotor's speeds.

local kind = beltsim.args.coupling or "one_way"
assert(kind == "one_way" or kind == "two_way" or kind == "none",
       "--set coupling=one_way|two_way|none, got " .. tostring(kind))
local crank_speed = -beltsim.rpm(800)  -- clockwise, with the belt
local shift_speed = -beltsim.rpm(600)

local alternator = { name = "alternator", centre = {0.0, 0.0}, radius = 0.027, inertia = 2e-3,
                     torque = { per_speed = -0.01 } }
if kind ~= "none" then
  alternator.inertia = 1e-4  -- the pulley and the spring's carrier; the rotor is behind the spring
  alternator.coupling = { inertia = 2e-3 - 1e-4, stiffness = 15, damping = 0.01, one_way = kind == "one_way" }
end

local drive = beltsim.scene {
  pulleys = {
    { name = "crankshaft", centre = {0.09, -0.27}, radius = 0.080, inertia = 0.02,
      speed = { beltsim.ramp{ t1 = 0.2, to = crank_speed, shape = "cosine" },
                beltsim.ramp{ t0 = 0.4, t1 = 0.43, to = shift_speed - crank_speed, shape = "cosine" },
                { mean_speed = -crank_speed, harmonics = {{2, 4.0, 0}} } } },
    { name = "tensioner", centre = {0.015, -0.12}, radius = 0.031, inertia = 5e-5, wrap = "back",
      tensioner = { pivot = {0.075, -0.14}, inertia = 1e-3, stiffness = 30,
                    damping = 0.05, friction_torque = 0.5, asymmetric = 3 } },
    alternator,
    { name = "pump", centre = {0.16, -0.06}, radius = 0.056, inertia = 1e-3,
      torque = { per_speed = -0.05 } },          -- 6 N·m at 120 rad/s
  },
  belt = { preset = "6PK", elements = 150, pretension = 280, direction = "cw" },
}

local result = drive:run { t_end = tonumber(beltsim.args.t_end) or 0.6, sample = 5e-4 }
print(string.format("t = %.3f s (%s): crankshaft %.2f, alternator %.2f, pump %.2f rad/s",
  result.t, kind, result.omega.crankshaft, result.omega.alternator, result.omega.pump))
