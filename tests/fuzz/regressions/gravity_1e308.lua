-- issue 12: gravity = 1e308 got "a few elements more or fewer usually works" (now: gravity, ρ·g·L, the value)
beltsim.scene {
  pulleys = { { name = "a", centre = {0, 0}, radius = 0.1 }, { name = "b", centre = {0.29, 0}, radius = 0.1 } },
  belt = { elements = 60, pretension = 500 },
  gravity = 1e308,
}
