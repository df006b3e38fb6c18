-- A sweep whose point mu = -1 fails (the scene refuses a negative friction coefficient) while
-- the other points run.
local drive = require "drive"
return beltsim.sweep {
  grid = { mu = {0.5, -1, 1.0} },
  run = function(p)
    local s = beltsim.scene(drive { mu = p.mu })
    local r = s:run { t_end = 0.02, sample = 1e-3, progress = false }
    return { slip = r.omega.driver - r.omega.driven }
  end,
}
