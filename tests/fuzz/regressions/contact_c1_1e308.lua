-- issue 12: contact.c1 = 1e308 gave a route with radii -nan (now: contact.c1 and its value)
beltsim.scene {
  pulleys = { { name = "a", centre = {0, 0}, radius = 0.1 }, { name = "b", centre = {0.29, 0}, radius = 0.1 } },
  belt = { elements = 60, pretension = 500 },
  contact = { c1 = 1e308 },
}
