// Workspace: the scratch of the evaluations of the model (MuJoCo's mjData without the state),
// owned by whoever evaluates (an integrator's system, a test) and filled stage by stage. A stage
// reads only what an earlier stage wrote for the same state: the contact records say which state
// they are of (contact_records.hpp), and the axes memo checks its angles.
#pragma once

#include <memory>
#include <vector>

#include "model/contact_records.hpp"
#include "model/forces.hpp"
#include "model/model.hpp"
#include "model/two_way.hpp"

namespace beltsim {

// A belt of kHalvesElements elements or more (two_way.hpp) is evaluated in two halves at once:
// the worker thread and each half's sums over elements (forces.hpp, Span).
struct Halves {
  explicit Halves(const Model& m);
  TwoWay two;
  // half p's sums: np pulley moments, the energy rates, np ∂M/∂Ω
  double* sum(int p) { return storage_.data() + first_ + p * stride_; }

 private:
  std::vector<double> storage_;
  int first_ = 0, stride_ = 0;
};

struct Workspace {
  // split: evaluate a belt of kHalvesElements or more in two halves at once
  explicit Workspace(const Model& m, bool split = true);
  // contact stage (contacts.hpp): the records of the last state the right-hand side evaluated, or
  // that a reader filled them at (contacts_at), one list per half of a split belt; read by the
  // forces, the Jacobian, the bristle rates, the Newton aids and the switching functions
  ContactRecords contacts;
  // position stage (sde.cpp): the elements' axes of the last evaluation, reused at the same angles
  AxisMemo axes;
  // the two halves' worker and sums; null when the belt is not split
  std::unique_ptr<Halves> halves;
};

}  // namespace beltsim
