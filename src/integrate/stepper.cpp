#include "integrate/stepper.hpp"

#include <stdexcept>

namespace beltsim {

std::unique_ptr<Stepper> make_rkf45();
std::unique_ptr<Stepper> make_rosenbrock();
std::unique_ptr<Stepper> make_esdirk();
std::unique_ptr<Stepper> make_trbdf2();

std::vector<std::string> stepper_names() { return {"esdirk32", "trbdf2", "ros34pw2", "rkf45"}; }

std::unique_ptr<Stepper> make_stepper(const std::string& name) {
  if (name == "rkf45") return make_rkf45();
  if (name == "ros34pw2") return make_rosenbrock();
  if (name == "esdirk32") return make_esdirk();
  if (name == "trbdf2") return make_trbdf2();
  std::string valid;
  for (const auto& n : stepper_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + name + "' (valid: " + valid + ")");
}

}  // namespace beltsim
