#pragma once
// spatter-bench surface: what searching the drawn surface along decals' axis lines costs
// (DecalProjector::findSurface through the renderer), against the frame it searches.

namespace spatter::bench {

int runSurfaceCommand(int argc, char** argv);

} // namespace spatter::bench
