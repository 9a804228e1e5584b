#pragma once
// Images on the host: float pixels, 1 to 4 interleaved channels, row 0 at the top as files store
// them. Reading goes through OpenImageIO, so any format it reads (PNG, JPEG, TIFF, EXR, HDR, ...)
// at 8, 16 or 32 bits works; 8/16-bit integer data arrive normalised to [0,1].
//
// Owns its pixels (a value type). Thread: any; reads and writes touch only the named file.

#include <cstddef>
#include <string>
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

struct ImageReadLimits {
    /// Images above this many pixels are refused before any pixel memory is allocated.
    long long maxPixels = 16384LL * 16384LL;
};

/// Reads the first subimage. Throws hfx::Error naming the file and OpenImageIO's reason for a
/// missing, unreadable, corrupt or truncated file, a zero or oversized resolution, or NaN/Inf.
Image readImage(const std::string& path, const ImageReadLimits& limits = {});

struct ImageSize {
    int width = 0, height = 0, channels = 0;
};
/// The first subimage's size from the file's header, no pixels read; the same errors as
/// readImage for a missing, unreadable, empty or oversized image.
ImageSize readImageSize(const std::string& path, const ImageReadLimits& limits = {});

/// Writes by extension: .png as 8-bit (values clamped to [0,1]), .exr as 32-bit float, anything
/// else OpenImageIO knows in its default format. Throws hfx::Error on failure.
void writeImage(const std::string& path, const Image& image);

} // namespace hfx
