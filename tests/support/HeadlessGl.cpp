#include "HeadlessGl.hpp"

#include <memory>

namespace spatter::test {

GlContext* headlessContext(std::string& why) {
    static std::unique_ptr<GlContext> context;
    static std::string error;
    static bool tried = false;
    if (!tried) {
        tried = true;
        HeadlessSettings settings;
        settings.debug = DebugOutput::On;
        Result<GlContext> c = GlContext::createHeadless(settings);
        if (c)
            context = std::make_unique<GlContext>(std::move(c).value());
        else
            error = c.error();
    }
    why = error;
    return context.get();
}

} // namespace spatter::test
