// The fields of a built scene's structs, each struct's listed once, as MuJoCo's mjxmacro.h lists
// mjModel's: the checkpoint's writer and reader (field_io.cpp, scene_io.cpp), the definition a built scene
// gives back (definition(), scene_io.hpp) and the comparison of two scenes (scene_difference)
// all expand these lists. A field is
//
//   X(kind, member, key, unit)   one the scenario gives: the definition's struct (PulleyDef,
//                                TensionerDef, CouplingDef, BeltDef) has a member of that name
//   D(kind, member, key, unit)   one the build derives
//
// key: the checkpoint's, after the struct's prefix ("arm." + "pivot"); where the scenario has the
// field it is the scenario's Lua name (scene/parameters.hpp). unit: SI, "" for a number without one.
// kind: how the checkpoint's text holds it (field_io.cpp, put_<kind> and get_<kind>):
//   real        a finite number              real_inf   a finite number or inf
//   integer     an int                       sign       -1, 0 or 1
//   flag        true or false                text       a quoted string
//   point       two numbers (x y)            places     a count, then "name" number pairs
//   reals       a count, then numbers        integers   a count, then integers
//   texts       a count, then strings        wrap, law, reading: a word (inside/back, the
//   timelaw     a torque or speed law's      friction law's name, rigidity/per_sde)
//               fields (BELTSIM_LAW_FIELDS)
// Counts and indices that depend on the rest of the scene (a pulley's number, one value per
// element) are checked where the struct is read. Adding a field means adding it here (and
// raising kCheckpointVersion, io/checkpoint_text.hpp).
#pragma once

namespace beltsim {

// ---- the model (model/model.hpp) ------------------------------------------------------------

#define BELTSIM_PULLEY_FIELDS(X, D)    \
  X(text, name, "name", "")            \
  X(point, centre, "centre", "m")      \
  X(real, radius, "radius", "m")       \
  X(real, inertia, "inertia", "kg·m²") \
  X(wrap, wrap, "wrap", "")

#define BELTSIM_ARM_FIELDS(X, D)                     \
  D(integer, pulley, "pulley", "")                   \
  X(point, pivot, "pivot", "m")                      \
  D(real, length, "length", "m")                     \
  X(real, inertia, "inertia", "kg·m²")               \
  X(real, stiffness, "stiffness", "N·m/rad")         \
  D(real, free_angle, "free_angle", "rad")           \
  X(real, damping, "damping", "N·m·s/rad")           \
  X(real, friction_torque, "friction_torque", "N·m") \
  X(real, friction_speed, "friction_speed", "rad/s") \
  X(real, asymmetric, "asymmetric", "")              \
  D(sign, press, "press", "")

#define BELTSIM_COUPLING_FIELDS(X, D)                \
  D(integer, pulley, "pulley", "")                   \
  X(real, inertia, "inertia", "kg·m²")               \
  X(real, stiffness, "stiffness", "N·m/rad")         \
  X(real, damping, "damping", "N·m·s/rad")           \
  X(flag, one_way, "one_way", "")                    \
  D(sign, sense, "sense", "")                        \
  X(real, hub_inertia, "hub_inertia", "kg·m²")       \
  X(real, lock_damping, "lock_damping", "N·m·s/rad") \
  X(real, drag_torque, "drag_torque", "N·m")

// (the derived lengths, mass and inertia must be > 0: scene_io.cpp checks each)
#define BELTSIM_BELT_FIELDS(X, D)              \
  D(integer, n, "elements", "")                \
  D(real, pitch, "pitch", "m")                 \
  D(real, rigid_length, "rigid_length", "m")   \
  D(real, mass, "mass", "kg")                  \
  D(real, rot_inertia, "rot_inertia", "kg·m²") \
  X(real, k, "sde.k", "N/m")                   \
  X(real, c, "sde.c", "N·s/m")                 \
  X(real, kt, "sde.kt", "N·m/rad")             \
  X(real, ct, "sde.ct", "N·m·s/rad")           \
  X(real, e_tra, "e_tra", "")                  \
  X(real, e_tor, "e_tor", "")

#define BELTSIM_CONTACT_FIELDS(X, D) \
  X(real, c1, "c1", "N/m²")          \
  X(real, c2, "c2", "N/m")           \
  X(real, b, "damping", "N·s/m")     \
  X(real, p_max, "p_max", "m")

#define BELTSIM_FRICTION_FIELDS(X, D)                    \
  X(real, dv, "dv", "m/s")                               \
  X(law, law, "law", "")                                 \
  X(real, static_ratio, "static_ratio", "")              \
  X(real, stribeck_speed, "stribeck_speed", "m/s")       \
  X(real, exponent, "exponent", "")                      \
  X(real, viscous, "viscous", "s/m")                     \
  X(real, bristle_stiffness, "bristle_stiffness", "1/m") \
  X(real, bristle_damping, "bristle_damping", "s/m")     \
  X(real, release_time, "release_time", "s")

// the model's own (its pulleys, arms, couplings, belt, contact and laws have the lists above;
// law_of is each element's law, written as integers)
#define BELTSIM_MODEL_FIELDS(X, D)    \
  X(real, gravity, "gravity", "m/s²") \
  X(flag, track_energy, "energy", "")

// ---- the drive (model/drive.hpp, model/laws.hpp, model/spray.hpp) ---------------------------

// (each pulley's, after its name: "pulley.drive")
#define BELTSIM_PULLEY_DRIVE_FIELDS(X, D)   \
  X(flag, kinematic, "drive.kinematic", "") \
  X(timelaw, torque, "torque", "N·m")       \
  X(timelaw, speed, "speed", "rad/s")

// (the drive's own: its pulleys' and spray zones' have their lists)
#define BELTSIM_DRIVE_FIELDS(X, D)           \
  D(real, restart_time, "restart_time", "s") \
  X(reals, mu, "belt.mu", "")

// a law's numbers and tables (its unit is the torque's or the speed's), then its ramps, sines and
// harmonics, each a list of its own
#define BELTSIM_LAW_FIELDS(X, D)                    \
  X(real, constant, "constant", "")                 \
  X(real, per_speed, "per_speed", "")               \
  X(reals, t, "table.t", "s")                       \
  X(reals, value, "table.value", "")                \
  X(reals, omega, "per_speed_table.omega", "rad/s") \
  X(reals, omega_value, "per_speed_table.value", "")

#define BELTSIM_RAMP_FIELDS(X, D) \
  X(real, t0, "t0", "s")          \
  X(real, t1, "t1", "s")          \
  X(real, from, "from", "")       \
  X(real, to, "to", "")           \
  X(flag, cosine, "cosine", "")

#define BELTSIM_SINE_FIELDS(X, D)       \
  X(real, mean, "mean", "")             \
  X(real, amplitude, "amplitude", "")   \
  X(real, frequency, "frequency", "Hz") \
  X(real, phase, "phase", "rad")

#define BELTSIM_HARMONIC_FIELDS(X, D) \
  X(real, order, "order", "")         \
  X(real, amplitude, "amplitude", "") \
  X(real, phase, "phase", "rad")      \
  X(real, mean_speed, "mean_speed", "rad/s")

#define BELTSIM_SPRAY_ZONE_FIELDS(X, D)        \
  X(point, centre, "centre", "m")              \
  X(real, radius, "radius", "m")               \
  X(real, mu, "mu", "")                        \
  X(real, from, "from", "s")                   \
  X(real_inf, to, "to", "s")                   \
  X(real, drying_length, "drying_length", "m") \
  X(flag, enabled, "enabled", "")              \
  D(flag, on, "on", "")

// each element's spray record, written as one column per field (one value per element)
#define BELTSIM_ELEMENT_SPRAY_FIELDS(X, D) \
  D(integer, zone, "zone", "")             \
  D(flag, drying, "drying", "")            \
  D(real, t_in, "t_in", "s")               \
  D(real, mu_wet, "mu_wet", "")            \
  D(real, t_wet, "t_wet", "s")             \
  D(real, rate, "rate", "1/s")

// ---- the scene (scene/scene_types.hpp, scene/route.hpp) -------------------------------------

#define BELTSIM_SPAN_FIELDS(X, D) \
  D(point, from, "from", "m")     \
  D(point, to, "to", "m")         \
  D(real, length, "length", "m")

#define BELTSIM_ARC_FIELDS(X, D)             \
  D(point, centre, "centre", "m")            \
  D(real, radius, "radius", "m")             \
  D(sign, sense, "sense", "")                \
  D(real, start_angle, "start_angle", "rad") \
  D(real, angle, "angle", "rad")

// (an input's unit and note come from the parameter table)
#define BELTSIM_INPUT_FIELDS(X, D) \
  D(text, name, "name", "")        \
  D(real, value, "value", "")      \
  D(text, text, "text", "")        \
  D(flag, given, "given", "")

#define BELTSIM_SITE_FIELDS(X, D) \
  D(integer, index, "index", "")  \
  D(point, centre, "centre", "m") \
  D(real, s, "s", "m")            \
  D(real, length, "length", "m")  \
  D(text, pulley, "pulley", "")   \
  D(places, meets, "meets", "m")  \
  D(places, leaves, "leaves", "m")

// the scene's own, after its model, drive, initial state and route (each per route entry or
// per span: checked where read)
#define BELTSIM_SCENE_FIELDS(X, D)                    \
  D(texts, route_names, "route.names", "")            \
  D(integers, route_pulleys, "route.pulleys", "")     \
  D(reals, penetration, "penetration", "m")           \
  D(reading, reading, "reading", "")                  \
  D(real, static_tension, "static_tension", "N")      \
  D(real, static_residual, "static_residual", "m/s²") \
  D(flag, static_retried, "static_retried", "")

}  // namespace beltsim
