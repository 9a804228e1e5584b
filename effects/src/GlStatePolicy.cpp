#include "hfx/effects/GlStatePolicy.h"

namespace hfx {

namespace {
thread_local GlStatePolicy tPolicy = GlStatePolicy::Restore;
} // namespace

void setGlStatePolicy(GlStatePolicy policy) { tPolicy = policy; }

GlStatePolicy glStatePolicy() { return tPolicy; }

} // namespace hfx
