#include "integrate/system.hpp"

namespace beltsim {

void LinearSolver::time_derivative(double*) const {}

}  // namespace beltsim
