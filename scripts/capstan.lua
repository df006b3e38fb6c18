-- The largest driver torque the paper's drive carries without gross slip, against the belt's wet
-- fraction (docs/sweeps.md): beltsim sweep scripts/capstan.lua
--
-- The paper's two-pulley drive (Kubas, §3): pulleys of r = 0.1 m 0.29 m apart, pretension 500 N,
-- μ = 1 dry and 0.2 wet, the wet part one stretch of the belt that travels with it. Each point
-- bisects the driver torque T: a run ramps the driver to T in 0.05 s and loads the driven pulley
-- in proportion to its speed (T at 700 rpm) for 0.4 s, two turns of the belt; the run slips
-- grossly when the driver turns more than 10 % faster than the driven pulley at any 10 ms (the
-- creep of a gripping belt is under 2 %). Beside it, the capstan (Euler–Eytelwein) limit with the
-- wet stretch over as much of one wrap as it can cover, ∫μ dθ = μ_dry (π - θ_wet) + μ_wet θ_wet
-- with θ_wet = min(w L / r, π):
--   capstan        T = 2 F0 r tanh(∫μ dθ / 2), the spans' tensions keeping their sum 2 F0
--   capstan_sum    T = (F_tight + F_slack) r tanh(∫μ dθ / 2), with the sum the last gripping run
--                  ended with (the largest and smallest element tensions at 0.4 s)
local l_p, r, F0, mu_dry, mu_wet = 0.29, 0.1, 500, 1.0, 0.2

-- true when the belt carries T without gross slip; the belt's largest and smallest tension at the end
local function grips(T, w)
  local drive = beltsim.scene {
    pulleys = {
      { name = "driver", centre = {0.0, 0.0}, radius = r, inertia = 0.025, torque = beltsim.ramp(0.05, -T) },
      { name = "driven", centre = {l_p, 0.0}, radius = r, inertia = 0.025,
        torque = { per_speed = -T / beltsim.rpm(700) } },
    },
    belt = {
      elements = 40, pretension = F0, direction = "cw",
      mu = function(site) if site.s < w * site.length then return mu_wet else return mu_dry end end,
    },
  }
  -- watched every 10 ms: a run that slips stops there
  local sim = drive:start { sample = 1e-2, progress = false }
  local slips = false
  while sim.t < 0.4 - 1e-9 and not slips do
    sim:advance(0.01)
    slips = sim:pulley("driver").omega / sim:pulley("driven").omega > 1.1
  end
  local tight, slack = -math.huge, math.huge
  for i = 0, 39 do
    local f = sim:element(i).tension
    tight, slack = math.max(tight, f), math.min(slack, f)
  end
  sim:close()
  return not slips, tight, slack
end

return beltsim.sweep {
  grid = { wet_fraction = {0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.5, 0.75, 1} },
  run = function(p)
    local w = p.wet_fraction
    local lo, hi = 0, 160  -- [N·m] grips at lo, slips at hi
    local tight, slack = F0, F0
    if grips(hi, w) then error(string.format("the belt grips at %g N·m: raise the bracket", hi)) end
    for _ = 1, 8 do  -- to 160 / 2^8 = 0.625 N·m
      local mid = (lo + hi) / 2
      local ok, f1, f2 = grips(mid, w)
      if ok then lo, tight, slack = mid, f1, f2 else hi = mid end
    end
    local L = 2 * l_p + 2 * math.pi * r
    local theta_wet = math.min(w * L / r, math.pi)
    local grip = math.tanh((mu_dry * (math.pi - theta_wet) + mu_wet * theta_wet) / 2)
    return { torque_grips = lo, torque_slips = hi, tight = tight, slack = slack,
             capstan = 2 * F0 * r * grip, capstan_sum = (tight + slack) * r * grip }
  end,
}
