#include "hfx/core/EdgeMode.h"

#include "hfx/core/Names.h"

namespace hfx {

namespace {
constexpr NamedValue<EdgeMode> kNames[] = {{EdgeMode::Wrap, "wrap"}, {EdgeMode::Clamp, "clamp"}, {EdgeMode::WrapU, "wrap-u"}};
}

const char* edgeModeName(EdgeMode edges) { return nameOf(kNames, edges); }

} // namespace hfx
