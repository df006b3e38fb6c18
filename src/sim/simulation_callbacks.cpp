// The callbacks of a live simulation (sim/simulation.hpp): every(dt), when(condition, action) and
// their cancel, registered with its Timeline. A callback's function runs with in_action_ set (a
// checkpoint it asks for is written once its time is done: Simulation::save), a when-condition
// with the state it is asked at in view_. The rest of Simulation is in simulation.cpp.
#include <cmath>
#include <stdexcept>

#include "integrate/timeline.hpp"
#include "io/number_text.hpp"
#include "model/laws.hpp"
#include "sim/scoped.hpp"
#include "sim/simulation.hpp"

namespace beltsim {

int Simulation::every(double dt, std::function<void()> fn) {
  require_open("every");
  if (!(dt > 0 && std::isfinite(dt)))
    throw std::invalid_argument("every: the interval must be > 0 s and finite (got " + rounded_text(dt) + " s)");
  callbacks_++;
  const int id = tl_->add_every(dt, [this, fn = std::move(fn)](double) {
    const Scoped<bool> acting(in_action_, true);
    fn();
  });
  every_dt_[id] = dt;
  return id;
}

int Simulation::when(std::function<bool()> cond, std::function<void()> action) {
  require_open("when");
  callbacks_++;
  auto c = [this, cond = std::move(cond)](double t, const Eigen::VectorXd& y) {
    const Scoped<View> at(view_, {t, &y});
    return cond();
  };
  // a simulation under way checks the condition now: its error is a callback's, as in run_to
  // (the script fails unless it catches the error; then the simulation may go on)
  try {
    return tl_->add_when(std::move(c), [this, action = std::move(action)](double) {
      const Scoped<bool> acting(in_action_, true);
      action();
    });
  } catch (const StoppedInCode& e) {  // Ctrl-C in the condition: no run to stop, the script stops
    callbacks_--;
    end_status_ = "interrupted", end_note_ = std::string("stopped (Ctrl-C or SIGTERM) in the Lua code of ") + e.what();
    throw;
  } catch (const std::exception& e) {
    callbacks_--;
    end_status_ = "failed", end_note_ = e.what();
    throw;
  } catch (...) {
    callbacks_--;
    end_status_ = "failed", end_note_ = "an error in a callback";
    throw;
  }
}

bool Simulation::cancel(int id) {
  const bool removed = tl_->remove(id);
  if (removed) callbacks_--, every_dt_.erase(id);
  return removed;
}

}  // namespace beltsim
