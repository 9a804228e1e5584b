#pragma once
// Images on the host: float pixels, 1 to 4 interleaved channels, row 0 at the top as files store
// them. The module reads and writes no file: the tools' codecs (hfx/tools/ImageFiles.h) or an
// engine's own loaders make them.
//
// Owns its pixels (a value type). Thread: any.

#include <cstddef>
#include <vector>

namespace hfx {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels; ///< width * height * channels, row-major, top row first

    bool empty() const { return pixels.empty(); }
    float& at(int x, int y, int c) {
        return pixels[(static_cast<size_t>(y) * width + x) * channels + c];
    }
    float at(int x, int y, int c) const {
        return pixels[(static_cast<size_t>(y) * width + x) * channels + c];
    }
};

} // namespace hfx
