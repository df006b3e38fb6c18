-- The largest driver torque the paper's drive carries without gross slip, against the belt's wet
-- fraction (docs/sweeps.md): beltsim sweep scripts/capstan.lua
--
-- The paper's two-pulley drive (Kubas, §3): pulleys of r = 0.1 m 0.29 m apart, pretension 500 N,
-- μ = 1 dry and 0.2 wet, the wet part one stretch of the belt that travels with it. Each point
-- bisects the driver torque T: a run ramps the driver to T and loads the driven pulley in
-- proportion to its speed (T at 700 rpm) for 0.4 s, two turns of the belt; the run slips grossly
-- when the driver turns more than 10 % faster than the driven pulley at any 10 ms (the creep of
-- a gripping belt is well under that). Beside
-- it, the capstan (Euler–Eytelwein) limit with the wet stretch over as much of one wrap as it can
-- cover: T = 2 F0 r tanh((μ_dry (π - θ_wet) + μ_wet θ_wet) / 2), θ_wet = min(w L / r, π).
local l_p, r, F0, mu_dry, mu_wet = 0.29, 0.1, 500, 1.0, 0.2

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
  sim:close()
  return not slips
end

return beltsim.sweep {
  grid = { wet_fraction = {0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.5, 0.75, 1} },
  run = function(p)
    local w = p.wet_fraction
    local lo, hi = 0, 120  -- [N·m] grips at lo; slips at hi, above the dry capstan limit of 91.7
    for _ = 1, 7 do  -- to 120 / 2^7 = 0.94 N·m
      local mid = (lo + hi) / 2
      if grips(mid, w) then lo = mid else hi = mid end
    end
    local L = 2 * l_p + 2 * math.pi * r
    local theta_wet = math.min(w * L / r, math.pi)
    local capstan = 2 * F0 * r * math.tanh((mu_dry * (math.pi - theta_wet) + mu_wet * theta_wet) / 2)
    return { torque_grips = lo, torque_slips = hi, capstan = capstan }
  end,
}
