#include "integrate/stepper.hpp"

#include <stdexcept>

namespace beltsim {

std::unique_ptr<Stepper> make_rkf45();
std::unique_ptr<Stepper> make_rosenbrock();
std::unique_ptr<Stepper> make_esdirk();
std::unique_ptr<Stepper> make_trbdf2();

std::vector<std::string> stepper_names() { return {"esdirk32", "trbdf2", "ros34pw2", "rkf45"}; }

std::vector<std::string> integrator_names() {
  std::vector<std::string> names = stepper_names();
  names.insert(names.end(), {"cvode", "cvode-fd"});
  return names;
}

namespace {
[[noreturn]] void unknown(const std::string& name) {
  throw std::invalid_argument("integrator: " + integrator_problem(name));
}
}  // namespace

std::string integrator_problem(const std::string& name) {
  std::string valid;
  for (const auto& n : integrator_names()) {
    if (n == name) return "";
    valid += (valid.empty() ? "" : ", ") + n;
  }
  return "unknown integrator '" + name + "' (valid: " + valid + ")";
}

void check_integrator(const std::string& name) {
  if (!integrator_problem(name).empty()) unknown(name);
}

std::unique_ptr<Stepper> make_stepper(const std::string& name) {
  if (name == "rkf45") return make_rkf45();
  if (name == "ros34pw2") return make_rosenbrock();
  if (name == "esdirk32") return make_esdirk();
  if (name == "trbdf2") return make_trbdf2();
  unknown(name);
}

}  // namespace beltsim
