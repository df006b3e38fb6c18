// The default of a number parameter of the scene's table (scene/parameters.hpp, whose
// parameters.cpp defines it), declared on its own for the initializers of the scene's structs
// (scene/scene_types.hpp): the table says where each value lives in those structs, so
// parameters.cpp includes them, and they cannot include the table's header back.
#pragma once

#include <string_view>

namespace beltsim {

// the default of a number parameter; throws std::logic_error for a key without one (a bug)
double parameter_default(std::string_view dotted);

}  // namespace beltsim
