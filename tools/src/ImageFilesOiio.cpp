// The OpenImageIO codec (HFX_IMAGE_IO=OpenImageIO, the default).
#include "hfx/tools/ImageFiles.h"

#include "hfx/core/Error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

namespace hfx {

namespace {

/// Tells OpenImageIO the same limits before it parses a header, so a file that claims a huge
/// size is refused by the reader instead of allocating for it; EXR files go through OpenEXR's
/// C core, which validates headers before allocating from them.
void limitReaders(const ImageReadLimits& limits) {
    const long long megabytes = std::max(1LL, limits.maxPixels * 4 * 4 / (1024 * 1024));
    OIIO::attribute("limits:imagesize_MB", int(std::min(megabytes, 1LL << 30)));
    OIIO::attribute("limits:channels", 64);
    OIIO::attribute("openexr:core", 1);
}

/// The file opened, its header checked against the limits.
std::unique_ptr<OIIO::ImageInput> openImage(const std::string& path, const ImageReadLimits& limits) {
    if (!std::filesystem::exists(path)) throw Error(str("image '", path, "' does not exist"));
    limitReaders(limits);
    // Channels as stored: OpenImageIO would multiply a PNG's colour by its alpha on reading
    // (associated alpha), which the light codec and the files' authors do not.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) throw Error(str("cannot read image '", path, "': ", OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw Error(str("image '", path, "' has an empty size ", spec.width, "x", spec.height,
                        "x", spec.nchannels));
    if (static_cast<long long>(spec.width) * spec.height > limits.maxPixels)
        throw Error(str("image '", path, "' is ", spec.width, "x", spec.height,
                        ", above the limit of ", limits.maxPixels, " pixels"));
    return in;
}

ImageSize readSize(const std::string& path, const ImageReadLimits& limits) {
    const auto in = openImage(path, limits); // held while its spec is read: the spec lives in it
    const OIIO::ImageSpec& spec = in->spec();
    return {spec.width, spec.height, std::min(spec.nchannels, 4)};
}

Image read(const std::string& path, const ImageReadLimits& limits) {
    const auto in = openImage(path, limits);
    const OIIO::ImageSpec& spec = in->spec();
    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.channels = std::min(spec.nchannels, 4);
    image.pixels.resize(static_cast<size_t>(image.width) * image.height * image.channels);
    if (!in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        throw Error(str("image '", path, "' is corrupt or truncated: ", in->geterror()));
    for (float v : image.pixels)
        if (!std::isfinite(v))
            throw Error(str("image '", path, "' holds NaN or infinite values"));
    return image;
}

void write(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels)
        throw Error(str("cannot write '", path, "': malformed image ", image.width, "x",
                        image.height, "x", image.channels));
    const std::string ext = std::filesystem::path(path).extension().string();
    const OIIO::TypeDesc format = (ext == ".exr" || ext == ".EXR") ? OIIO::TypeDesc::FLOAT
                                  : (ext == ".png" || ext == ".PNG") ? OIIO::TypeDesc::UINT8
                                                                     : OIIO::TypeDesc::UNKNOWN;
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw Error(str("cannot write '", path, "': ", OIIO::geterror()));
    OIIO::ImageSpec spec(image.width, image.height, image.channels,
                         format == OIIO::TypeDesc::UNKNOWN ? OIIO::TypeDesc::UINT8 : format);
    if (ext == ".jpg" || ext == ".jpeg" || ext == ".JPG") spec.attribute("Compression", "jpeg:85");
    if (!out->open(path, spec))
        throw Error(str("cannot write '", path, "': ", out->geterror()));
    if (!out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !out->close())
        throw Error(str("writing '", path, "' failed: ", out->geterror()));
}

} // namespace

const ImageCodec* openImageIoCodec() {
    static const std::string name = str("OpenImageIO ", OIIO_VERSION_STRING);
    static const ImageCodec codec{name.c_str(), &read, &readSize, &write};
    return &codec;
}

} // namespace hfx
