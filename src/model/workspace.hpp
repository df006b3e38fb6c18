// Workspace: the scratch of one evaluation of the model (MuJoCo's mjData without the state),
// owned by whoever evaluates (an integrator's system, the observer, a test) and filled stage by
// stage. Nothing in it outlives the evaluation as an input: a stage reads only what an earlier
// stage of the same evaluation wrote (the axes memo is the exception, and it checks its angles).
#pragma once

#include <memory>
#include <vector>

#include "model/contact_law.hpp"
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
  // contact stage (contact_pass, contact_law.hpp): the pairs in contact, one list per half of the
  // belt (only contacts[0] when the belt is not split); read by the forces, the Jacobian and
  // whoever asks the evaluation's contacts
  ContactList contacts[2];
  // position stage (sde.cpp): the elements' axes of the last evaluation, reused at the same angles
  AxisMemo axes;
  // the two halves' worker and sums; null when the belt is not split
  std::unique_ptr<Halves> halves;
};

}  // namespace beltsim
