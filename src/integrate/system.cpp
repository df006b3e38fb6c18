#include "integrate/system.hpp"

namespace beltsim {

void OdeSystem::time_derivative(double*) const {}

}  // namespace beltsim
