// SUNDIALS CVODE (variable-order BDF with Newton) as the peer integrator, behind the same live
// Integrator interface as the one-step methods (integrate/integrator.hpp): samples at exact times by CVODE's own interpolation (CVodeGetDky), events landed on
// with CVodeSetStopTime and the integration restarted there (CVodeReInit), the stop flag, and
// DivergenceError naming the time and the component. Two variants:
//   "cvode"     our analytic Jacobian J = ∂F/∂y assembled sparse, solved by KLU
//   "cvode-fd"  CVODE's own difference-quotient Jacobian with its dense LU (CVODE has no
//               difference-quotient Jacobian for sparse matrices)
#pragma once

#include <string>
#include <vector>

#include "integrate/driver.hpp"

namespace beltsim {

std::vector<std::string> cvode_names();  // {"cvode", "cvode-fd"}
bool is_cvode(const std::string& name);

DriveResult drive_cvode(OdeSystem& sys, const std::string& name, const Tolerances& tol, const DriveOptions& opt,
                        Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress = {});
std::unique_ptr<Integrator> make_cvode_integrator(const std::string& name, OdeSystem& sys, const Tolerances& tol);

}  // namespace beltsim
