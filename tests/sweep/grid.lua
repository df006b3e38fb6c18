-- A small sweep for the tests: the paper's two-pulley drive, 0.02 s of it, on a 2 x 3 grid.
-- beltsim.args.fail_at = "300,0.5": that point raises an error (a failing point).
local fail_at = beltsim.args.fail_at
local drive = require "drive"
return beltsim.sweep {
  grid = { pretension = {300, 500}, mu = {0.3, 0.6, 1.0} },
  run = function(p)
    if fail_at == p.pretension .. "," .. p.mu then error("asked to fail at " .. fail_at) end
    local s = beltsim.scene(drive { pretension = p.pretension, mu = p.mu })
    local r = s:run { t_end = 0.02, sample = 1e-3, progress = false }
    return { slip = r.omega.driver - r.omega.driven, omega = r.omega, steps = r.steps }
  end,
}
