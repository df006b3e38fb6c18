-- The automotive drive the C++ tests build (support/presets.cpp): automotive.lua's at 280 N, the
-- idler fixed, or on its arm with --set arm=true (the tests give it the paper's torques, the arm's
-- damping and friction, the wet stretch).
local automotive = require "automotive"
beltsim.scene(automotive { arm = beltsim.args.arm and {} or false, belt = { pretension = 280 } }):run {}
