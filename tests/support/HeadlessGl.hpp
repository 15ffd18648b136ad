#pragma once
// The headless OpenGL context that the GL tests of one process share.

#include "spatter/render/GlContext.hpp"

#include <string>

namespace spatter::test {

// The process's headless context (debug output on, so GL errors are counted), or nullptr with
// `why` set when none can be created. Created at the first call.
GlContext* headlessContext(std::string& why);

} // namespace spatter::test
