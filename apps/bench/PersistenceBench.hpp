#pragma once
// spatter-bench persistence: the time to save a decal system's state to bytes and to load it back
// (DecalPersistence.hpp), to memory and through a file, and the bytes a decal takes in a save.

namespace spatter::bench {

int runPersistenceCommand(int argc, char** argv);

} // namespace spatter::bench
