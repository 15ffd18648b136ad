#pragma once
// spatter-bench characters: the frame cost of decals on animated characters (skinned dummies with a
// hundred decals each, posed every frame), against the same characters without decals.

namespace spatter::bench {

int runCharactersCommand(int argc, char** argv);

} // namespace spatter::bench
