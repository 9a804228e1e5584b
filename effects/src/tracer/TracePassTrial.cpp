#include "hfx/effects/tracer/TracePassTrial.h"

#include <algorithm>
#include <cmath>

namespace hfx {

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(mid), v.end());
    const double upper = v[mid];
    if (v.size() % 2 == 1) return upper;
    return 0.5 * (*std::max_element(v.begin(), v.begin() + std::ptrdiff_t(mid)) + upper);
}

} // namespace

const char* tracePassName(TracePass pass) {
    switch (pass) {
    case TracePass::Auto: return "auto";
    case TracePass::InDraw: return "in the draw";
    case TracePass::Compute: return "compute pass";
    }
    return "?";
}

TracePass TracePassTrial::next() const {
    if (decided()) return chosen_;
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
    if (++s.recorded > kWarmUp) s.counted.push_back(ms);
    if (int(inDraw_.counted.size()) >= kCounted && int(compute_.counted.size()) >= kCounted)
        chosen_ = median(compute_.counted) < kComputeMargin * median(inDraw_.counted) ? TracePass::Compute
                                                                                      : TracePass::InDraw;
}

TracePassTrialReport TracePassTrial::report() const {
    return {.chosen = chosen_,
            .inDrawMs = median(inDraw_.counted),
            .computeMs = median(compute_.counted),
            .inDrawDraws = int(inDraw_.counted.size()),
            .computeDraws = int(compute_.counted.size())};
}

} // namespace hfx
