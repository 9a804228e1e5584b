#include "hfx/core/EdgeMode.h"

namespace hfx {

const char* edgeModeName(EdgeMode edges) {
    switch (edges) {
    case EdgeMode::Wrap: return "wrap";
    case EdgeMode::Clamp: return "clamp";
    case EdgeMode::WrapU: return "wrap-u";
    }
    return "?";
}

} // namespace hfx
