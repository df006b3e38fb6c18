#include "integrate/make_integrator.hpp"

#include "integrate/cvode.hpp"
#include "integrate/stepper.hpp"

namespace beltsim {

std::unique_ptr<Integrator> make_integrator(const std::string& name, const OdeSystem& sys, const Tolerances& tol,
                                            double h_max) {
  check_integrator(name);
  check_tolerances(tol);
  if (is_cvode(name)) return make_cvode_integrator(name, sys, tol);
  return make_one_step(make_stepper(name), sys, tol, h_max);
}

}  // namespace beltsim
