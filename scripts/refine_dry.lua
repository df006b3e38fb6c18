-- The paper's dry second at 60, 120 and 240 elements, with the contact law and the bending
-- damping given per length (equal to the paper's per-element values at 60 elements), and with the
-- paper's per-element values as printed: the first converges as elements are added, the second
-- does not (each element of a finer belt presses on the pulley as hard as a coarse one). The
-- "Element count" table of docs/model.md comes from this script.
-- SI units; counter-clockwise positive.

local route = 2 * 0.29 + 2 * math.pi * 0.1      -- m, the pitch line round the two pulleys
local pitch60 = route / 60                       -- m, the paper's element pitch
local paper = { c1 = 3.0256e9, c2 = 6.5e5, damping = 300, p_max = 1e-3 }
local per_length = {
  c1_per_length = paper.c1 / pitch60,            -- N/m³
  c2_per_length = paper.c2 / pitch60,            -- N/m²
  damping_per_length = paper.damping / pitch60,  -- N·s/m²
  p_max = paper.p_max,
}

local function drive(elements, contact, bending)
  local belt = {
    elements = elements, pretension = 500, direction = "cw",
    EA = 1.52e5, EI = 0.026, axial_damping = 20.5, mass_per_length = 0.096, mu = 1.0,
  }
  for k, v in pairs(bending) do belt[k] = v end
  return beltsim.scene {
    pulleys = {
      { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = 0.025,
        torque = beltsim.ramp(0.3, -70.0) },
      { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = 0.025,
        torque = { per_speed = -70.0 / beltsim.rpm(700) } },
    },
    belt = belt, contact = contact, friction = { dv = 1e-5 }, gravity = 9.81,
  }
end

-- --set 'counts="60,120,240,480,960"' and --set 'form="per length"' (or "per element") choose the runs
-- (default: 60, 120 and 240 elements in both forms)
local args = beltsim.args
local counts = {}
for c in tostring(args.counts or "60,120,240"):gmatch("%d+") do counts[#counts + 1] = tonumber(c) end
local forms = {
  { name = "per length", contact = per_length, bending = { bending_viscosity = 0.05 * pitch60 } },
  { name = "per element", contact = paper, bending = { bending_damping = 0.05 } },
}
print("form         elements  driver [rad/s]  driven [rad/s]  slip [rad/s]  slack, tight span [N]  " ..
  "driver slip arc [m]  steps  wall [s]")
for _, form in ipairs(forms) do
  if args.form == nil or args.form == form.name then
    for _, n in ipairs(counts) do
      local sim = drive(n, form.contact, form.bending):start {
        sample = 1e-3, progress = false,
        out = string.format("out/refine_dry/%s-%d", form.name:gsub(" ", "_"), n),
      }
      local r = sim:run_to(0.9)
      -- span tensions and the driver's slip arc: means of 101 samples over 0.9-1 s
      local slack, tight, arc, k = 0, 0, 0, 0
      local steps, wall = r.steps, r.wall
      sim:every(1e-3, function()
        local a, b = sim:span("driver", "driven"), sim:span("driven", "driver")
        slack, tight = slack + math.min(a, b), tight + math.max(a, b)
        arc, k = arc + sim:pulley("driver").slip_arc, k + 1
      end)
      r = sim:run_to(1.0)
      steps, wall = steps + r.steps, wall + r.wall
      local d, e = sim:pulley("driver").omega, sim:pulley("driven").omega
      print(string.format("%-12s %8d  %14.4f  %14.4f  %12.4f  %9.1f, %9.1f  %19.4f  %5d  %8.1f", form.name, n,
        d, e, e - d, slack / k, tight / k, arc / k, steps, wall))
      sim:close()
    end
  end
end
