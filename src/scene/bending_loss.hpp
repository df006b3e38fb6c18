// The bending dampers' share of the power a drive transmits, estimated before it runs
// (docs/model.md, "Bending loss"), and the warning of the run's first lines when
// it is large (scene_warnings, scene:info().warnings).
//
// Speeds: the laws' steady values (a ramp's end value, a table's last value, a sine's mean; the
// harmonics average out). With a kinematic pulley its steady speed sets the belt speed
// v = |Ω|·R; without one, v balances the free pulleys' torques on a belt that loses nothing,
// Σ M_j(s_j·v/R_j)·s_j/R_j = 0 (s_j the sense the belt turns pulley j). A law given as a Lua
// function is not evaluated (a kinematic pulley's then gives no speed, a free pulley's no torque).
//
// Transmitted power: what the free pulleys' torque laws take out (Σ max(0, −M_j·Ω_j)) or put in,
// whichever is larger, at those speeds.
//
// Dissipated power: where the belt runs onto or off a pulley of radius R, each joint's bend goes
// from 0 to p/R (p the pitch). Its profile along the belt is that of a tensioned beam with a
// viscous bending moment, EI·κ'' + η·v·κ''' = T·κ: it decays over ℓ = 1/λ, λ the positive root of
// η·v·λ³ + EI·λ² = T (ℓ = sqrt(EI/T) when the damping is light, (η·v/T)^(1/3) when it dominates),
// with EI = k_t·p, η = c_t·p and T the static tension. A chain of joints p apart smooths that
// profile over one pitch; the power of one transition is then
//   P = c_t·v²/(R²·p) · (p − ℓ·(1 − e^(−p/ℓ)))
// (η·v²/(2R²·ℓ) for p ≪ ℓ, c_t·v²/R² for p ≫ ℓ), two transitions per pulley. Against measured
// energy.dissipated_bending on the automotive drive it is within −1 … +14 % over two decades of
// power, two speeds and two element counts (docs/model.md gives the runs).
#pragma once

#include <optional>
#include <string>

namespace beltsim {

struct Scene;
struct TimeSpeedLaw;

// A law's steady value as the estimate reads it (above): once its ramps and tables have ended, its
// sines at their means and its harmonics averaged out, at speed omega [rad/s]; nullopt for a law
// given as Lua code (not evaluated here)
std::optional<double> steady_value(const TimeSpeedLaw& law, double omega);

struct BendingLoss {
  double belt_speed = 0;   // [m/s] at the laws' steady values
  double transmitted = 0;  // [W] taken by the loads (or put in by the free drivers)
  double dissipated = 0;   // [W] the bending dampers' estimate, every wrap's two transitions
  // dissipated / transmitted
  double share() const { return dissipated / transmitted; }
};

// The estimate above; nullopt when the drive's steady speed or its transmitted power cannot be
// found (no kinematic speed and no balance of the free pulleys' torques, nothing transmitted, a
// belt without bending damping).
std::optional<BendingLoss> estimate_bending_loss(const Scene& sc);

// The belt's steady speed along its travel [m/s], signed (> 0: the way belt.direction says), as the
// estimate finds it (above); nullopt when it cannot be found. Pulley j then turns at
// sense_j·v/R_j (Scene::senses()).
std::optional<double> steady_belt_speed(const Scene& sc);

// The fastest belt speed the balance of the free pulleys' torques is sought below [m/s].
inline constexpr double kFastestBeltSpeed = 1e3;
// Whether steady_belt_speed's search found the free pulleys' torques still driving the belt on at
// kFastestBeltSpeed (false where a kinematic pulley's speed sets the belt's, or a law is code): no
// steady speed exists below it, and the drive speeds up until the belt slips on a pulley or a
// pulley runs away.
bool drives_past_fastest(const Scene& sc);

// Above this share of the transmitted power the run's first lines warn: a PK belt's whole loss is
// a few per cent (published efficiencies 95–98 %, docs/belts.md).
inline constexpr double kBendingLossWarn = 0.05;

// The warning when the estimate's share exceeds kBendingLossWarn: the figures, the key that sets
// the damping and the presets; "" otherwise.
std::string bending_loss_warning(const Scene& sc);

}  // namespace beltsim
