-- The paper's two-pulley drive with a dry belt (Kubas, §3, Figs 6–13).
-- SI units; counter-clockwise positive. Parameters not given here take the paper's values
-- (docs/lua-api.md); the pulley inertias are ours (docs/model.md).
-- Parameters (--set KEY=VALUE), for variants of the drive (the accuracy matrix of
-- docs/accuracy.md): elements (default 60), inertia of both pulleys [kg·m²] (default 0.025),
-- sample, the interval of the time series' rows [s] (default 1e-3).

local elements = beltsim.args.elements or 60
local inertia = beltsim.args.inertia or 0.025
local sample = beltsim.args.sample or 1e-3

local drive = beltsim.scene {
  pulleys = {
    -- driving torque: ramp to 70 N·m in 0.3 s, clockwise (Fig. 7a)
    { name = "driver", centre = {0.0, 0.0}, radius = 0.1, inertia = inertia,
      torque = beltsim.ramp(0.3, -70.0) },
    -- resistance: 70 N·m at 700 rpm, opposing the rotation (Fig. 7b)
    { name = "driven", centre = {0.29, 0.0}, radius = 0.1, inertia = inertia,
      torque = { per_speed = -70.0 / beltsim.rpm(700) } },
  },
  belt = {
    elements = elements,
    pretension = 500,           -- N
    direction = "cw",           -- the driver turns clockwise, the belt with it
    EA = 1.52e5,                -- N      (paper's c_tra, read as an axial rigidity: docs/model.md)
    EI = 0.026,                 -- N·m²   (paper's c_tor, a bending rigidity)
    axial_damping = 20.5,       -- N·s    (paper's b_tra, per unit length)
    bending_damping = 0.05,     -- N·m·s/rad per SDE (paper's b_tor)
    mass_per_length = 0.096,    -- kg/m
    mu = 1.0,
  },
  contact = { c1 = 3.0256e9, c2 = 6.5e5, damping = 300, p_max = 1e-3 },
  friction = { dv = 1e-5 },
  gravity = 9.81,
  energy = true,
}

-- the paper's selected element starts where the upper span meets the driven pulley
local result = drive:run {
  t_end = 1.0,
  sample = sample,
  probe = {0.29, 0.1},
  -- a 10 s clip, ten times slower than life (a frame every 3.3 ms of simulated time: the belt
  -- moves about one element per frame at full speed), coloured by the belt tension so that its
  -- fall round each pulley shows; the belt's deviation from its path magnified ten times; a
  -- PNG every 0.1 s of simulated time (every 30th frame)
  frames = {
    fps = 30, slowdown = 10, size = {1280, 720},
    quantity = "tension", range = {0, 1000},
    magnify = 10,
    png = true, png_every = 30,
    video = "paper_dry.mp4",
  },
}
print(string.format("t = %.3f s: driver %.3f rad/s, driven %.3f rad/s",
  result.t, result.omega.driver, result.omega.driven))
if result.frames > 0 then
  print(string.format("%d frames: %s/frames/ (PNG, every 30th) and %s/paper_dry.mp4",
    result.frames, result.csv:match("(.*)/"), result.csv:match("(.*)/")))
end
