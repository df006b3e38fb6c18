// The tensioner arms of a scene (TensionerDef in scene_types.hpp; the arm's law at the top of
// model/tensioner.cpp). Arm a holds its pulley's centre c at the installed angle
// ψ_i = atan2(c - pivot), length L = |c - pivot|. In the static state the belt's moment about the
// pivot, M_b = g·H (H the belt's hub load on the pulley, g = ∂c/∂ψ), is held by the spring:
//   -k·(ψ_i - ψ0) + M_b = 0,   so   ψ0 = ψ_i - M_b/k,
// and the spring presses the pulley on the belt in the sense of -M_b. M_b grows in proportion to
// the belt's tension, so a preload P (the spring's moment at ψ_i; angle0 gives P = k·|ψ_i - angle0|)
// sets the tension: build_scene scales the pretension by P/|M_b| until they agree.
#include <cmath>

#include "io/number_text.hpp"
#include "model/contacts.hpp"
#include "model/forces.hpp"
#include "model/observables.hpp"
#include "scene/build.hpp"
#include "scene/validate.hpp"

namespace beltsim::build {

void validate_tensioner(const PulleyDef& p) {
  if (!p.tensioner) return;
  const TensionerDef& t = *p.tensioner;
  const std::string w = "pulley '" + p.name + "'.tensioner.";
  require_finite(w + "pivot x", t.pivot.x(), "m");
  require_finite(w + "pivot y", t.pivot.y(), "m");
  require_positive(w + "pivot's distance from the pulley's centre", (p.centre - t.pivot).norm(), "m");
  if (p.kinematic)
    throw ParameterError(
        "pulley '" + p.name + "'",
        "a pulley on a tensioner arm turns freely; give it a torque (or none), not a prescribed speed");
}

void make_arms(const SceneDef& d, Model& m) {
  m.arms.clear();
  for (size_t j = 0; j < d.pulleys.size(); ++j) {
    const PulleyDef& p = d.pulleys[j];
    if (!p.tensioner) continue;
    const TensionerDef& t = *p.tensioner;
    Arm a;
    a.pulley = static_cast<int>(j);
    a.pivot = t.pivot;
    a.length = (p.centre - t.pivot).norm();
    a.inertia = t.inertia;
    a.stiffness = t.stiffness;
    a.damping = t.damping;
    a.friction_torque = t.friction_torque;
    a.friction_speed = t.friction_speed;
    a.asymmetric = t.asymmetric;
    a.free_angle = std::atan2(p.centre.y() - t.pivot.y(), p.centre.x() - t.pivot.x());  // until balanced
    m.pulleys[j].arm = m.n_arm();
    m.arms.push_back(a);
  }
}

void set_arm_angles(const Model& m, Eigen::VectorXd& y) {
  for (int a = 0; a < m.n_arm(); ++a) {
    const Vec2 d = m.pulleys[m.arms[a].pulley].centre - m.arms[a].pivot;
    y[m.arm_coord(a)] = std::atan2(d.y(), d.x());
  }
}

double arm_belt_moment(const Scene& sc, const ContactRecords& contacts, int a) {
  const Model& m = sc.model;
  Vec2 hub;
  belt_torque(contacts, m.arms[a].pulley, &hub);
  return hub.dot(arm_lever(m, a, sc.y0.data()));
}

void balance_arms(Scene& sc) {
  Model& m = sc.model;
  ContactRecords contacts;
  fill_contacts(m, sc.drive, 0.0, sc.y0.data(), contacts);
  for (int a = 0; a < m.n_arm(); ++a) {
    Arm& arm = m.arms[a];
    const double Mb = arm_belt_moment(sc, contacts, a);
    if (!(Mb != 0)) {
      throw ParameterError("pulley '" + m.pulleys[arm.pulley].name + "'.tensioner",
                           "the belt has no moment about the pivot at the installed angle (the pivot "
                           "lies on the line of the hub load); move the pivot");
    }
    arm.free_angle = sc.y0[m.arm_coord(a)] - Mb / arm.stiffness;
    arm.press = Mb < 0 ? 1 : -1;
  }
}

void check_angle0_side(const Scene& sc, const SceneDef& d, int pulley) {
  const TensionerDef& t = *d.pulleys[pulley].tensioner;
  if (!t.angle0) return;
  const Model& m = sc.model;
  const int a = m.pulleys[pulley].arm;
  ContactRecords contacts;
  fill_contacts(m, sc.drive, 0.0, sc.y0.data(), contacts);
  const double Mb = arm_belt_moment(sc, contacts, a);
  const double psi = sc.y0[m.arm_coord(a)];
  // the spring holds the belt's moment: -k·(ψ_i - ψ0) + M_b = 0, so ψ_i - ψ0 has M_b's sign; on
  // the other side the spring turns the arm the way the belt does, off the belt, and no tension
  // holds it
  if ((psi - *t.angle0) * Mb > 0) return;
  const double mirror = psi - std::copysign(std::abs(psi - *t.angle0), Mb);
  reject("pulley '" + m.pulleys[pulley].name + "'.tensioner.angle0",
         "puts the spring's free angle on the side that turns the arm away from the belt: at the installed angle " +
             rounded_text(psi, 6) + " rad the belt turns the arm toward " + (Mb > 0 ? "larger" : "smaller") +
             " angles, so the spring must be free at " + (Mb > 0 ? "a smaller" : "a larger") +
             " angle to press the pulley on the belt (" + rounded_text(mirror, 6) +
             " rad gives the same preload); as given, no tension at rest could hold the arm",
         *t.angle0, "rad");
}

std::optional<double> tensioner_preload(const SceneDef& d) {
  std::optional<double> preload;
  std::string setter;
  for (const PulleyDef& p : d.pulleys) {
    if (!p.tensioner || !p.tensioner->sets_tension()) continue;
    const TensionerDef& t = *p.tensioner;
    const std::string w = "pulley '" + p.name + "'.tensioner";
    if (t.preload && t.angle0) throw ParameterError(w, "give preload [N·m] or angle0 [rad], not both");
    if (preload)
      throw ParameterError(
          w, "only one tensioner can set the belt's tension by its preload or angle0 ('" + setter +
                 "' does already); leave them out here and the spring's free angle holds the belt's tension");
    for (const char* key : {"belt.pretension", "belt.rest_length", "belt.strain"})
      if (d.given.count(key))
        throw ParameterError(w, std::string("its preload or angle0 sets the belt's tension at rest; leave out ") + key +
                                    " or the tensioner's preload/angle0");
    if (t.preload) {
      preload = *t.preload;  // > 0: the parameter table's rule (validate)
    } else {
      const Vec2 c = p.centre - t.pivot;
      const double psi = std::atan2(c.y(), c.x());
      preload = t.stiffness * std::abs(psi - *t.angle0);
      if (!(*preload > 0))
        throw ParameterError(w + ".angle0", "the spring's free angle equals the installed angle (" + rounded_text(psi) +
                                                " rad): the spring would hold no tension");
      // a windup past a turn is no tensioner's: an angle in degrees, or a turn added
      if (std::abs(psi - *t.angle0) > 2 * M_PI) {
        // (past 2π it cannot be an angle in (-π, π]: likely degrees)
        const std::string degrees =
            std::abs(*t.angle0) > 2 * M_PI
                ? " (" + rounded_text(*t.angle0, 6) + "° would be " + rounded_text(*t.angle0 * M_PI / 180, 4) + " rad)"
                : "";
        reject(w + ".angle0",
               "winds the spring by " + rounded_text(std::abs(psi - *t.angle0), 4) + " rad from the installed angle " +
                   rounded_text(psi, 6) + " rad, more than a turn; the angle is in radians" + degrees +
                   ", measured as the installed angle is: atan2 of the pulley's centre from the pivot, in (-π, π]",
               *t.angle0, "rad");
      }
    }
    setter = p.name;
  }
  return preload;
}

}  // namespace beltsim::build
