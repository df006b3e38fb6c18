// A pulley's law as one line of text: a Lua expression that beltsim.scene reads back to the same
// law (its numbers as number_text writes them), but for a Lua function, written as
// "function at file:line". For events.csv (a law changed at a pause), parameters.csv and the
// console's messages.
#pragma once

#include <string>

#include "model/laws.hpp"

namespace beltsim {

std::string law_text(const TimeSpeedLaw& law);

}  // namespace beltsim
