-- An ordinary script for the quick form: beltsim sweep plain.lua --set pretension=300,500 --set mu=0.3,1
local drive = require "drive"
local s = beltsim.scene(drive { pretension = beltsim.args.pretension, mu = beltsim.args.mu })
s:run { t_end = beltsim.args.t_end or 0.02, sample = 1e-3, progress = false }
