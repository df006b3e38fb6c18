// Exact checkpoints of a built Scene (and of a Model, a Drive, a law, a vector on their own: a live
// simulation's drive differs from its scene's after changes of torque laws or μ).
//
// The format is line-oriented text, one field per line, each line opening with the field's
// keyword, so a person can read a checkpoint and a reader of another version stops at the first
// field it does not expect:
//
//   scene 1                          <- object and format version
//   model 1
//   gravity 0x1.39eb851eb851fp+3
//   pulleys 2
//   pulley "driver"                  <- strings quoted, \" \\ \n escaped
//   pulley.centre 0x0p+0 0x0p+0
//   ...
//   y0 364 0x1.2p-3 ...              <- sequences: keyword, count, values
//   ...
//   end scene
//
// Doubles are C99 hex floats (std::hexfloat), read back with std::strtod, so every finite value,
// ±0, subnormals and ±inf come back bit for bit; a NaN comes back as a NaN of the same sign (its
// payload is not kept). Text after '#' at the end of a line, blank lines and '#' lines are
// ignored. A malformed or truncated input throws std::runtime_error("checkpoint: ...") naming
// the field that was expected. Writers use the classic locale whatever the stream's; the reader's
// std::strtod assumes LC_NUMERIC is "C" (the program never changes it).
//
// Adding a field to Scene, Model, Drive, Pulley, TimeSpeedLaw, Belt, Contact, Friction, Route or
// ElementSite means adding it here and raising kCheckpointVersion.
#pragma once

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/model.hpp"
#include "scene/scene.hpp"

namespace beltsim {

inline constexpr int kCheckpointVersion = 5;

void write_scene(std::ostream& out, const Scene& sc);
Scene read_scene(std::istream& in);

void write_model(std::ostream& out, const Model& m);
Model read_model(std::istream& in);
void write_drive(std::ostream& out, const Drive& d);
Drive read_drive(std::istream& in);

// `key` names the object in the text (e.g. "torque"), and must match on reading
void write_law(std::ostream& out, const TimeSpeedLaw& law, const std::string& key = "law");
TimeSpeedLaw read_law(std::istream& in, const std::string& key = "law");

// one line: key, count, values
void write_vector(std::ostream& out, const Eigen::VectorXd& v, const std::string& key = "vector");
Eigen::VectorXd read_vector(std::istream& in, const std::string& key = "vector");
void write_vector(std::ostream& out, const std::vector<double>& v, const std::string& key = "vector");
std::vector<double> read_std_vector(std::istream& in, const std::string& key = "vector");

}  // namespace beltsim
