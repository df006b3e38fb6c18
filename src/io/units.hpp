// The unit of every quantity beltsim writes, in one table: the columns of timeseries.csv
// (`<pulley>.omega`, `span_<a>_<b>.tension`, `probe.slip_velocity`, `energy.*`, `t`) and the
// element and pulley fields (`omega`, `angle`, `x`, `phi`, `normal`, `mu`, ...). A column is looked
// up by its last dotted component ("driver.omega" → "omega" → "rad/s"); `energy.*` is J whatever
// follows the dot. Units are SI, written as in docs/outputs.md ("N·m", UTF-8 middle dot); "" for a
// dimensionless quantity (μ) and for a name the table does not know.
#pragma once

#include <string>
#include <string_view>

namespace beltsim {

std::string unit_of(std::string_view column);

}  // namespace beltsim
