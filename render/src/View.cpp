#include "spatter/render/View.hpp"

namespace spatter {

namespace {
constexpr View kViews[] = {View::Final, View::Albedo, View::Normal, View::Depth, View::Ids, View::Coverage};
}

const char* toString(View view) {
    switch (view) {
    case View::Final:
        return "final";
    case View::Albedo:
        return "albedo";
    case View::Normal:
        return "normal";
    case View::Depth:
        return "depth";
    case View::Ids:
        return "ids";
    case View::Coverage:
        return "coverage";
    }
    return "unknown";
}

Result<View> parseView(const std::string& name) {
    for (View v : kViews)
        if (name == toString(v)) return v;
    return fail("view '" + name + "' is not one of final, albedo, normal, depth, ids, coverage");
}

} // namespace spatter
