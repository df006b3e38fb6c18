-- A serpentine accessory drive of six pulleys on a 6PK belt (its preset, docs/belts.md) in the
-- per-length forms: the crankshaft at 800 rpm with its second-order firing pulsation, a
-- spring-loaded tensioner arm, the alternator behind a one-way decoupler, a back-side idler,
-- the water pump and the AC compressor. The idlers and the alternator's pulley are light
-- (4e-5 to 1e-4 kg·m²). Used by docs/accuracy.md for the cost of a step:
--   beltsim run scripts/serpentine.lua --set n=200 --set t_end=0.3
-- Parameters (--set KEY=VALUE): n element count (default 200), t_end [s] (default 0.3).
-- Its review figures at speed, belt power loss by channel among them (docs/summary.md):
--   beltsim summary out/serpentine --from 0.2
-- SI units; counter-clockwise positive.

local n = tonumber(beltsim.args.n) or 200
local crank_speed = -beltsim.rpm(800)  -- clockwise, with the belt
local pitch60 = (2 * 0.29 + 2 * math.pi * 0.1) / 60  -- m: the paper's contact constants are per element of this pitch

local drive = beltsim.scene {
  pulleys = {
    { name = "crankshaft", centre = {0.09, -0.27}, radius = 0.080, inertia = 0.02,
      speed = { beltsim.ramp{ t1 = 0.2, to = crank_speed, shape = "cosine" },
                { mean_speed = -crank_speed, harmonics = {{2, 4.0, 0}} } } },
    { name = "tensioner", centre = {0.015, -0.12}, radius = 0.031, inertia = 5e-5, wrap = "back",
      tensioner = { pivot = {0.075, -0.14}, inertia = 1e-3, stiffness = 30,
                    damping = 0.05, friction_torque = 0.5, asymmetric = 3 } },
    { name = "alternator", centre = {0.0, 0.0}, radius = 0.027, inertia = 1e-4,
      torque = { per_speed = -0.01 },
      coupling = { inertia = 1.9e-3, stiffness = 15, damping = 0.01, one_way = true } },
    { name = "idler", centre = {0.08, 0.01}, radius = 0.03, inertia = 4e-5, wrap = "back" },
    { name = "pump", centre = {0.16, -0.06}, radius = 0.056, inertia = 1e-3,
      torque = { per_speed = -0.05 } },
    { name = "compressor", centre = {0.24, -0.21}, radius = 0.06, inertia = 1.5e-3,
      torque = { per_speed = -0.04 } },
  },
  belt = { preset = "6PK", elements = n, pretension = 300, direction = "cw" },
  contact = { c1_per_length = 3.0256e9 / pitch60, c2_per_length = 6.5e5 / pitch60,
              damping_per_length = 300 / pitch60, p_max = 1e-3 },
  energy = true,  -- the work and dissipation per channel: beltsim summary's belt power loss rows
}

local r = drive:run { t_end = tonumber(beltsim.args.t_end) or 0.3, sample = 5e-4 }
print(string.format("%d elements, t = %.3f s: crankshaft %.2f, alternator %.2f, compressor %.2f rad/s; %d steps, %.1f s",
  n, r.t, r.omega.crankshaft, r.omega.alternator, r.omega.compressor, r.steps, r.wall))
