-- The bending dampers' power a run measures against the estimate the scene makes before it runs
-- (scene:info().bending_loss, src/scene/bending_loss.hpp): the accessory drive of
-- docs/automotive.md (its layout, the idler fixed, no pulsation), the crankshaft ramped to its
-- speed in 0.05 s, the alternator and the pump loaded with 0.01 and 0.05 N·m·s/rad; the power is
-- the slope of energy.dissipated_bending over 0.1-0.2 s. The study table of docs/model.md
-- (bending loss) comes from this script; --set only=K runs case K alone.
-- SI units; counter-clockwise positive.

local cases = {  -- { bending damping per SDE (nil: the 6PK preset), elements, crankshaft rpm }
  { 0.05, 150, 800 }, { 0.005, 150, 800 }, { 0.0005, 150, 800 }, { 0.05, 300, 800 }, { 0.0025, 300, 800 },
  { 0.05, 150, 1600 }, { 0.005, 150, 1600 }, { nil, 150, 800 }, { nil, 300, 800 }, { nil, 150, 1600 },
}

local function drive(damping, elements, rpm)
  local belt = damping and { bending_damping = damping } or beltsim.belts["6PK"]
  belt.elements, belt.pretension, belt.direction = elements, 280, "cw"
  return beltsim.scene {
    pulleys = {
      { name = "crankshaft", centre = {0.09, -0.27}, radius = 0.080, inertia = 0.02,
        speed = beltsim.ramp{ t1 = 0.05, to = -beltsim.rpm(rpm), shape = "cosine" } },
      { name = "tensioner", centre = {0.015, -0.12}, radius = 0.031, inertia = 5e-5, wrap = "back" },
      { name = "alternator", centre = {0.0, 0.0}, radius = 0.027, inertia = 2e-3, torque = { per_speed = -0.01 } },
      { name = "pump", centre = {0.16, -0.06}, radius = 0.056, inertia = 1e-3, torque = { per_speed = -0.05 } },
    },
    belt = belt,
    energy = true,
  }
end

print("damping [N·m·s/rad]  elements  rpm   transmitted [W]  estimate [W]  measured [W]  estimate/measured  " ..
  "crankshaft [N·m]  steps  wall [s]")
local only = tonumber(beltsim.args.only)
for k, c in ipairs(cases) do
  if only == nil or only == k then
    local scene = drive(c[1], c[2], c[3])
    local estimate = scene:info().bending_loss
    local sim = scene:start { progress = false, out = string.format("out/bending_loss_study/%d", k) }
    local r = sim:run_to(0.1)
    local steps, wall = r.steps, r.wall
    local e1 = sim:energy().dissipated_bending
    local torque, samples = 0, 0
    sim:every(1e-3, function()
      torque, samples = torque + sim:pulley("crankshaft").torque, samples + 1
    end)
    r = sim:run_to(0.2)
    steps, wall = steps + r.steps, wall + r.wall
    local measured = (sim:energy().dissipated_bending - e1) / 0.1
    print(string.format("%-19s  %8d  %4d  %15.1f  %12.2f  %12.2f  %17.3f  %16.2f  %5d  %8.1f",
      c[1] and tostring(c[1]) or "6PK preset", c[2], c[3], estimate.transmitted, estimate.dissipated, measured,
      estimate.dissipated / measured, -torque / samples, steps, wall))
    sim:close()
  end
end
