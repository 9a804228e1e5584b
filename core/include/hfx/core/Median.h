#pragma once
// The median of timings, the one the benches and the exact tracer's pass trial take: the middle
// value, the upper of the two middle ones for an even count, 0 for none.

#include <algorithm>
#include <vector>

namespace hfx {

inline double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

} // namespace hfx
