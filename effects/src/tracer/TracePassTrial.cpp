#include "hfx/effects/tracer/TracePassTrial.h"

#include "hfx/core/Median.h"

#include <cmath>

namespace hfx {

const char* tracePassName(TracePass pass) {
    switch (pass) {
    case TracePass::Auto: return "auto";
    case TracePass::InDraw: return "in the draw";
    case TracePass::Compute: return "compute pass";
    }
    return "?";
}

TracePass TracePassTrial::next() const {
    if (decided()) return report_.chosen;
    return compute_.begun <= inDraw_.begun ? TracePass::Compute : TracePass::InDraw;
}

void TracePassTrial::began(TracePass pass) {
    if (!decided()) ++side(pass).begun;
}

void TracePassTrial::record(TracePass pass, double ms) {
    if (decided() || pass == TracePass::Auto) return;
    Side& s = side(pass);
    if (!std::isfinite(ms) || ms < 0.0) {
        --s.begun; // not counted: the side times another draw
        return;
    }
    if (++s.recorded <= kWarmUp) return;
    s.counted.push_back(ms);
    report_.inDrawMs = median(inDraw_.counted);
    report_.computeMs = median(compute_.counted);
    report_.inDrawDraws = int(inDraw_.counted.size());
    report_.computeDraws = int(compute_.counted.size());
    if (report_.inDrawDraws >= kCounted && report_.computeDraws >= kCounted)
        report_.chosen = report_.computeMs < kComputeMargin * report_.inDrawMs ? TracePass::Compute : TracePass::InDraw;
}

} // namespace hfx
