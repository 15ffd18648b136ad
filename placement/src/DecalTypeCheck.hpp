#pragma once
// The checks of a decal type's own fields that DecalSystem::registerType makes.

#include "spatter/core/DecalType.hpp"

#include <string>

namespace spatter {

// Why the fields of `t` (all but its name) make no decal type, or empty.
std::string decalTypeProblem(const DecalType& t);

} // namespace spatter
