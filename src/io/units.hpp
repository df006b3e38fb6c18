// The unit of every quantity beltsim writes, in one table: the columns of timeseries.csv
// (`<pulley>.omega`, `span_<a>_<b>.tension`, `probe.slip_velocity`, `energy.*`, `t`) and the
// element and pulley fields (`omega`, `angle`, `x`, `phi`, `normal`, `mu`, ...), and the fields of
// scene:run{}'s result (run_result_unit: the figures of a sweep's quick form). A column is looked
// up by its last dotted component ("driver.omega" → "omega" → "rad/s"); `energy.*` is J whatever
// follows the dot. Units are SI, written as in docs/outputs.md ("N·m", UTF-8 middle dot); "" for a
// dimensionless quantity (μ) and for a name the table does not know.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace beltsim {

class OutputDir;

std::string unit_of(std::string_view column);
// unit_of's unit of a name the table knows; nullopt for one it does not ("" is a dimensionless
// quantity's: μ, creep)
std::optional<std::string> known_unit(std::string_view column);

// The unit of a field of scene:run{}'s result table (docs/lua-api.md), named as a sweep's quick
// form flattens it into summary.csv ("omega.driver" rad/s, "steps" "", a count; "check.tension" "",
// a relative error; "check.warned_t" s), from the same table; nullopt for a text or boolean field
// (csv, interrupted, check.over) and a name the result table has not (a field a script added)
std::optional<std::string> run_result_unit(std::string_view field);

// the fields of scene:run{}'s result under prefix ("check." -> "speed", "tension", ...), each
// with its run_result_unit: those of a table a result holds (its check estimate)
std::vector<std::pair<std::string, std::string>> run_result_units(std::string_view prefix);

// the unit a CSV header names between brackets at its end ("hub load [N]" -> "N", typed_unit's
// form); nullopt when it names none
std::optional<std::string> bracketed_unit(std::string_view header);
// the unit a CSV header names: bracketed_unit's, else unit_of(header)
std::string header_unit(std::string_view header);

// A CSV file's units file beside it, for a reader given the folder alone (pandas, MATLAB): named
// after the file ("timeseries.csv" -> "timeseries_units.csv"; units_file_name), written whole, a
// header "column,unit" and a row per column in the file's order: its unit as unit_of gives it,
// "1" for a dimensionless number, empty for a column that has none (text, or a sweep's figure
// whose unit is not known: nullopt). docs/outputs.md, docs/sweeps.md
using ColumnUnits = std::vector<std::pair<std::string, std::optional<std::string>>>;
std::string units_file_name(const std::string& csv);
void write_units_file(const OutputDir& dir, const std::string& csv, const ColumnUnits& columns);
// the units file beside the CSV file at path csv, as write_units_file wrote it; nullopt when there
// is none (a folder written before it) or it is not one
std::optional<ColumnUnits> read_units_file(const std::string& csv);

// a magnitude typical of the unit in a belt drive, from a car's accessory drive to an
// industrial one: `beltsim compare` takes rtol times it as a column's absolute tolerance, so that
// one rtol means the same in every unit and a value near 0 is compared at that scale (docs/
// testing-your-scenario.md). 1 for a unit it does not know.
double unit_scale(std::string_view unit);

// a unit as typed on a command line, in the form of unit_of: "N.m", "N*m" and "Nm" are "N·m";
// "1" and "-" the dimensionless ""
std::string typed_unit(std::string_view typed);

}  // namespace beltsim
