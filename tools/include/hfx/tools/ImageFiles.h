#pragma once
// Image files for the demo, the tools and the tests: the module itself (core, compute, effects)
// reads no file, an engine brings its own loaders and hands the module plain Images
// (hfx/core/Image.h) and SurfaceMaps.
//
// Two codecs, one chosen at build time (HFX_IMAGE_IO):
// - OpenImageIO (the default): anything it reads (PNG, JPEG, TIFF, EXR, HDR, ...), 8, 16 or 32
//   bits; it brings about 360 MB of libraries (GDAL, OpenVDB, ffmpeg) along;
// - light: stb_image and stb_image_write (PNG, JPEG, BMP, TGA, GIF, PSD, PNM, Radiance HDR) and
//   tinyexr (OpenEXR), a few hundred KB: what scripts/bundle.sh ships.
// The light codec is built in either case, so the tests hold both to the same behaviour.
//
// 8/16-bit integer data arrive normalised to [0,1]; row 0 is the top row, as files store it.
// Thread: any; reads and writes touch only the named file.

#include "hfx/core/Image.h"
#include "hfx/core/SurfaceMaps.h"

#include <string>

namespace hfx {

struct ImageReadLimits {
    /// Images above this many pixels are refused before any pixel memory is allocated.
    long long maxPixels = 16384LL * 16384LL;
};

struct ImageSize {
    int width = 0, height = 0, channels = 0;
};

/// One implementation of the file operations below.
struct ImageCodec {
    const char* name; ///< "OpenImageIO 2.4.7", "stb + tinyexr"
    Image (*read)(const std::string& path, const ImageReadLimits& limits);
    ImageSize (*readSize)(const std::string& path, const ImageReadLimits& limits);
    void (*write)(const std::string& path, const Image& image);
};

/// The build's codec (HFX_IMAGE_IO).
const ImageCodec& imageCodec();
/// stb + tinyexr, always built.
const ImageCodec& lightImageCodec();
/// OpenImageIO, or null in a build without it (HFX_IMAGE_IO=light).
const ImageCodec* openImageIoCodec();

/// Reads the first subimage (at most 4 channels). Throws hfx::Error naming the file and the
/// reason for a missing, unreadable, corrupt or truncated file, a format the codec does not
/// read, a zero or oversized resolution, or NaN/Inf.
Image readImage(const std::string& path, const ImageReadLimits& limits = {});
/// The first subimage's size from the file's header, no pixels read; the same errors as
/// readImage for a missing, unreadable, empty or oversized image.
ImageSize readImageSize(const std::string& path, const ImageReadLimits& limits = {});
/// Writes by extension: .png as 8-bit (values clamped to [0,1]), .exr as 32-bit float, .jpg at
/// quality 85, anything else the codec knows in its default format. Throws hfx::Error naming
/// the file for a malformed image, an unknown extension or a failed write.
void writeImage(const std::string& path, const Image& image);

/// Reads a height map and, when their paths are not empty, a normal and a colour map of the same
/// size (surfaceMapsFromImages). Throws hfx::Error naming the file that is missing, corrupt, out
/// of range or of another size; nothing is returned half-read.
SurfaceMaps readSurfaceMaps(const std::string& heightMap, const std::string& normalMap, const std::string& colorMap,
                            const ImageReadLimits& limits = {});

} // namespace hfx
