#include "spatter/placement/SpawnResult.hpp"

namespace spatter {

const char* toString(SpawnStatus status) {
    switch (status) {
    case SpawnStatus::Placed:
        return "placed";
    case SpawnStatus::Missed:
        return "missed";
    case SpawnStatus::GrazingAngle:
        return "grazing_angle";
    case SpawnStatus::NotReceiver:
        return "not_receiver";
    case SpawnStatus::InvalidRay:
        return "invalid_ray";
    case SpawnStatus::InvalidType:
        return "invalid_type";
    case SpawnStatus::InvalidArgument:
        return "invalid_argument";
    case SpawnStatus::AreaLimit:
        return "area_limit";
    }
    return "unknown";
}

} // namespace spatter
