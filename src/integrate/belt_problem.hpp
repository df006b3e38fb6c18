// The belt model as an OdeProblem (integrate/system.hpp): F, the tolerances' scales and the
// friction band's resolution, the switching functions of the contact and friction laws, and the
// names and sanity check of the state's components.
#pragma once

#include "integrate/system.hpp"
#include "model/model.hpp"
#include "model/rhs.hpp"

namespace beltsim {

class BeltProblem final : public OdeProblem {
 public:
  // d: the drive the run holds (Simulation); changes to it apply from the next evaluation
  BeltProblem(const Model& m, const Drive& d);
  int size() const override { return model_.n_state(); }
  void rhs(double t, const double* y, double* dy) override { beltsim::rhs(model_, drive_, t, y, dy, &ws_); }
  // atol applies per natural size of each component (atol_scale), in words:
  static constexpr const char* kNaturalSizes =
      "0.1 m (positions), 1 rad (angles), 1 m/s (element velocities), 10 rad/s (element spins), "
      "1 rad/s (pulley speeds), 1 J (energies), 1/σ0 (LuGre bristle deflections)";
  double atol_scale(int k) const override;
  double resolution(int k) const override;
  // the answer (OdeProblem::answer): the speeds of the pulleys, the tensioner arms' angles, the
  // coupled rotors' speeds, then the axial force of the SDE nearest each of the points `spans`
  // (the middles of the route's spans: the span tensions users read) [rad/s, rad, N]
  void set_spans(std::vector<Vec2> spans) { spans_ = std::move(spans); }
  int answer_size() const override;
  void answer(double t, const double* y, double* a, int count) override;
  void answer_error(double t, const double* y, const double* e, double* da, int count) override;
  double answer_scale(int k) const override;
  // every component but the elements' velocities (x, y, spin): their error is held through the
  // elements' positions and angles, the pulley speeds and the span tensions (StepController)
  bool in_state_norm(int k) const override;
  // the LuGre bristles' deflections: each is a friction force's state (σ0·z of μ's part), which
  // the answer's span tensions and pulley speeds integrate; in the state norm, 10 times looser and
  // averaged over the whole belt, their error drifted the driver's speed while it slipped on a
  // LuGre stretch, by 5e-4 at rtol 1e-3 and 1e-4 alike (docs/accuracy.md)
  bool held_each(int k) const override;
  // the speeds and arm angles: a span tension reads the SDE's damper, so the elements' velocities,
  // which cross the friction band's and the contact's kinks inside a step (docs/integration.md,
  // Dense output)
  bool checked_inside(int k) const override;
  std::string describe_answer(int k) const override;
  int switch_count() const override;
  // from the contact records of (t, y) with every pair (model/contacts.hpp), kept in the workspace
  void switches(double t, const double* y, double* g) override;
  std::string describe(int k) const override;
  std::string check(double t, const double* y) const override;
  // a free pulley whose applied torque at (t, y) passes the largest torque its belt could ever
  // carry on it, kAbsurdTorque·F·r: F = k·l0^e_tra, the axial force that stretches the belt by its
  // own length (EA for a linear belt), at the pulley's radius r. A drive's torques are a few
  // percent of it (the paper's belt, the default: EA = 152 kN, r = 0.05 m, F·r = 7600 N·m against tens of
  // N·m); past it the law is a slip of its unit or sign of magnitude (1e30 from a function, 1e300
  // from t = 0), whose stop was blamed on an element or on no component (trial 16). The largest
  // such pulley is named: "pulley 'driven'.torque = 1e+30 N·m at t = 0.005 s ..."
  std::string absurd_input(double t, const double* y) const override;
  static constexpr double kAbsurdTorque = 1;
  const Model& model() const { return model_; }
  const Drive& drive() const { return drive_; }
  // the right-hand side's scratch, which the Jacobian shares (BeltLinearSolver)
  Workspace& workspace() { return ws_; }

 private:
  const Model& model_;
  const Drive& drive_;
  // the right-hand side's, the Jacobian's, the Newton aids' and the switching functions'
  // (model/workspace.hpp)
  Workspace ws_;
  std::vector<Vec2> spans_;    // where the answer's span tensions are taken
  std::vector<double> y_minus_e_;  // answer_error's scratch
  std::vector<int> nearest_;       // answer's and answer_error's: the SDE nearest each span's point
  // the number of answer quantities before the span tensions (speeds, arm angles, rotor speeds)
  int head() const;
  // fills nearest_ at y for the span tensions among the first `count` answer quantities and
  // returns how many there are
  int span_sdes(const double* y, int count);
};

}  // namespace beltsim
