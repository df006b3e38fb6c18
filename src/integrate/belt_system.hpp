// The belt as an integrator sees it: the problem, the ring linear solver and the Newton aids,
// owned together over one Model and one Drive, and given to an integrator as an OdeSystem.
#pragma once

#include "integrate/belt_linear_solver.hpp"
#include "integrate/belt_newton.hpp"
#include "integrate/belt_problem.hpp"
#include "integrate/system.hpp"

namespace beltsim {

class BeltSystem {
 public:
  // d: the drive the run holds (Simulation); changes to it apply from the next evaluation
  BeltSystem(const Model& m, const Drive& d)
      : problem(m, d), linear(m, d, problem.workspace()), aids(m, d, problem.workspace()) {}
  BeltSystem(const BeltSystem&) = delete;
  BeltSystem& operator=(const BeltSystem&) = delete;
  operator OdeSystem() { return OdeSystem(problem, &linear, &aids); }

  BeltProblem problem;
  BeltLinearSolver linear;  // shares the problem's workspace
  BeltNewtonAids aids;      // reads the contact records in the problem's workspace
};

}  // namespace beltsim
