-- The automotive drive of the tests, defined here once: paper §4's layout as
-- scripts/automotive_tensioner.lua places it (crankshaft, tensioner idler on the belt's back on its
-- arm, alternator, coolant pump; 150 elements, clockwise). The Lua tests' scripts start with it
-- (support/scenes.hpp, automotive_text: a local function automotive), the C++ tests' scenes read it
-- through automotive_scene.lua (require "automotive"). automotive(o) is the scene's table, for
-- beltsim.scene: o.crank and o.pump the crankshaft's and the pump's torque (none when nil), o.arm
-- the arm's keys besides its pivot, inertia and stiffness (false: the idler fixed, no arm), o.belt
-- more keys of the belt, o.spray the spray zones.
return function(o)
  local arm = o.arm ~= false and { pivot = {0.075, -0.14}, inertia = 1e-3, stiffness = 30 } or nil
  for k, v in pairs(o.arm or {}) do arm[k] = v end
  local belt = { elements = 150, direction = 'cw' }
  for k, v in pairs(o.belt or {}) do belt[k] = v end
  return {
    pulleys = {
      { name = 'crankshaft', centre = {0.09, -0.27}, radius = 0.080, inertia = 0.02, torque = o.crank },
      { name = 'tensioner', centre = {0.015, -0.12}, radius = 0.031, inertia = 5e-5, wrap = 'back', tensioner = arm },
      { name = 'alternator', centre = {0.0, 0.0}, radius = 0.027, inertia = 2e-3 },
      { name = 'pump', centre = {0.16, -0.06}, radius = 0.056, inertia = 1e-3, torque = o.pump },
    },
    belt = belt,
    spray = o.spray,
  }
end
