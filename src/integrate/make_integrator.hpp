// The integrator a run names: a one-step method (integrate/stepper.hpp) or CVODE
// (integrate/cvode.hpp), the one place that knows both.
#pragma once

#include <memory>
#include <string>

#include "integrate/integrator.hpp"

namespace beltsim {

// Every integrator a run accepts (integrate/stepper.hpp integrator_names()). The system must
// outlive the integrator. h_max: largest step [s] (0: none). Throws std::invalid_argument for an
// unknown name or a tolerance outside (0, 1) / a negative or non-finite atol.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const OdeSystem& sys, const Tolerances& tol,
                                            double h_max = 0);

}  // namespace beltsim
