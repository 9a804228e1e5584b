// The light codec: stb_image / stb_image_write (Debian's libstb) and tinyexr (libtinyexr), a
// few hundred KB where OpenImageIO brings 360 MB. Always built; the build's codec when
// HFX_IMAGE_IO=light (scripts/bundle.sh).
#include "hfx/tools/ImageFiles.h"

#include "hfx/core/Error.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>

namespace hfx {
namespace {

std::string extensionOf(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

void checkExists(const std::string& path) {
    if (!std::filesystem::exists(path)) throw Error(str("image '", path, "' does not exist"));
}

void checkSize(const std::string& path, long long width, long long height, int channels,
               const ImageReadLimits& limits) {
    if (width <= 0 || height <= 0 || channels <= 0)
        throw Error(str("image '", path, "' has an empty size ", width, "x", height, "x", channels));
    if (width * height > limits.maxPixels)
        throw Error(str("image '", path, "' is ", width, "x", height, ", above the limit of ", limits.maxPixels,
                        " pixels"));
}

void checkFinite(const std::string& path, const Image& image) {
    for (float v : image.pixels)
        if (!std::isfinite(v)) throw Error(str("image '", path, "' holds NaN or infinite values"));
}

bool isExr(const std::string& path) {
    // The magic number, not the name: a file is what its bytes say.
    unsigned char magic[4] = {};
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
        const size_t n = std::fread(magic, 1, 4, f);
        std::fclose(f);
        return n == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
    }
    return false;
}

/// tinyexr's error text (freed here) in an hfx::Error naming the file.
[[noreturn]] void exrFailure(const std::string& path, const char* what, const char* err) {
    const std::string reason = err ? err : "unknown tinyexr error";
    if (err) FreeEXRErrorMessage(err);
    throw Error(str("cannot read image '", path, "' (", what, "): ", reason));
}

/// An EXR's header, parsed (freed on scope exit).
struct ExrHeader {
    EXRHeader header;
    explicit ExrHeader(const std::string& path) {
        InitEXRHeader(&header);
        EXRVersion version;
        if (ParseEXRVersionFromFile(&version, path.c_str()) != TINYEXR_SUCCESS)
            throw Error(str("cannot read image '", path, "': not an OpenEXR file tinyexr reads"));
        if (version.multipart || version.non_image)
            throw Error(str("image '", path, "' is a multi-part or deep OpenEXR file; one plain image is needed"));
        const char* err = nullptr;
        if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &err) != TINYEXR_SUCCESS) {
            // A parse that fails part-way has filled some of the header (no destructor runs for
            // a constructor that throws).
            FreeEXRHeader(&header);
            exrFailure(path, "header", err);
        }
    }
    ~ExrHeader() { FreeEXRHeader(&header); }
    int width() const { return header.data_window.max_x - header.data_window.min_x + 1; }
    int height() const { return header.data_window.max_y - header.data_window.min_y + 1; }
};

/// The channels to read, in the order an Image holds them: R, G, B, A where the file has them
/// (EXR stores channels sorted by name), else the file's order; at most four.
std::vector<int> exrChannelOrder(const EXRHeader& h) {
    std::vector<int> order;
    for (const char* name : {"R", "G", "B", "A"})
        for (int c = 0; c < h.num_channels; ++c)
            if (std::strcmp(h.channels[c].name, name) == 0) order.push_back(c);
    if (order.empty() || (order.size() == 1 && h.num_channels > 1))
        for (int c = 0; c < h.num_channels && order.size() < 4; ++c)
            if (std::find(order.begin(), order.end(), c) == order.end()) order.push_back(c);
    if (order.size() > 4) order.resize(4);
    return order;
}

ImageSize readExrSize(const std::string& path, const ImageReadLimits& limits) {
    ExrHeader h(path);
    const int channels = int(exrChannelOrder(h.header).size());
    checkSize(path, h.width(), h.height(), channels, limits);
    return {h.width(), h.height(), channels};
}

Image readExr(const std::string& path, const ImageReadLimits& limits) {
    ExrHeader h(path);
    const std::vector<int> order = exrChannelOrder(h.header);
    checkSize(path, h.width(), h.height(), int(order.size()), limits);
    if (h.header.tiled)
        throw Error(str("image '", path, "' is a tiled OpenEXR file; the light image codec reads scanline files"));
    for (int c = 0; c < h.header.num_channels; ++c) h.header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    EXRImage exr;
    InitEXRImage(&exr);
    const char* err = nullptr;
    if (LoadEXRImageFromFile(&exr, &h.header, path.c_str(), &err) != TINYEXR_SUCCESS) exrFailure(path, "pixels", err);
    std::unique_ptr<EXRImage, int (*)(EXRImage*)> owned(&exr, &FreeEXRImage);
    Image image;
    image.width = exr.width;
    image.height = exr.height;
    image.channels = int(order.size());
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    for (int k = 0; k < image.channels; ++k) {
        const auto* plane = reinterpret_cast<const float*>(exr.images[order[size_t(k)]]);
        for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
            image.pixels[p * image.channels + size_t(k)] = plane[p];
    }
    checkFinite(path, image);
    return image;
}

ImageSize readSize(const std::string& path, const ImageReadLimits& limits) {
    checkExists(path);
    if (isExr(path)) return readExrSize(path, limits);
    int w = 0, h = 0, channels = 0;
    if (!stbi_info(path.c_str(), &w, &h, &channels))
        throw Error(str("cannot read image '", path, "': ", stbi_failure_reason(),
                        " (the light image codec reads PNG, JPEG, BMP, TGA, GIF, PSD, PNM, HDR and EXR)"));
    checkSize(path, w, h, channels, limits);
    return {w, h, std::min(channels, 4)};
}

Image read(const std::string& path, const ImageReadLimits& limits) {
    const ImageSize size = readSize(path, limits); // the header checked before any pixel memory
    if (isExr(path)) return readExr(path, limits);
    int w = 0, h = 0, channels = 0;
    Image image;
    auto fill = [&](const auto* data, float scale) {
        if (!data) throw Error(str("image '", path, "' is corrupt or truncated: ", stbi_failure_reason()));
        image.width = w;
        image.height = h;
        image.channels = std::min(channels, 4);
        image.pixels.resize(size_t(w) * h * image.channels);
        for (size_t p = 0; p < size_t(w) * h; ++p)
            for (int c = 0; c < image.channels; ++c)
                image.pixels[p * image.channels + size_t(c)] = float(data[p * size_t(channels) + size_t(c)]) * scale;
        stbi_image_free(const_cast<void*>(static_cast<const void*>(data)));
    };
    if (stbi_is_hdr(path.c_str()))
        fill(stbi_loadf(path.c_str(), &w, &h, &channels, 0), 1.0f);
    else if (stbi_is_16_bit(path.c_str()))
        fill(stbi_load_16(path.c_str(), &w, &h, &channels, 0), 1.0f / 65535.0f);
    else
        fill(stbi_load(path.c_str(), &w, &h, &channels, 0), 1.0f / 255.0f);
    if (image.width != size.width || image.height != size.height)
        throw Error(str("image '", path, "' read as ", image.width, "x", image.height, " after a header of ", size.width,
                        "x", size.height));
    checkFinite(path, image);
    return image;
}

void writeExr(const std::string& path, const Image& image) {
    // Channels sorted by name, as OpenEXR stores them: Y alone; B, G, R; A, B, G, R; two as R, G.
    static const char* const kNames[5][4] = {{}, {"Y"}, {"G", "R"}, {"B", "G", "R"}, {"A", "B", "G", "R"}};
    static const int kSource[5][4] = {{}, {0}, {1, 0}, {2, 1, 0}, {3, 2, 1, 0}};
    const int n = image.channels;
    const size_t count = static_cast<size_t>(n);
    const size_t pixels = size_t(image.width) * image.height;
    std::vector<std::vector<float>> planes(count, std::vector<float>(pixels));
    std::vector<unsigned char*> planePointers(count);
    std::vector<EXRChannelInfo> infos(count);
    std::vector<int> types(count, TINYEXR_PIXELTYPE_FLOAT);
    for (int k = 0; k < n; ++k) {
        for (size_t p = 0; p < pixels; ++p) planes[size_t(k)][p] = image.pixels[p * n + size_t(kSource[n][k])];
        planePointers[size_t(k)] = reinterpret_cast<unsigned char*>(planes[size_t(k)].data());
        std::memset(&infos[size_t(k)], 0, sizeof(EXRChannelInfo));
        std::strncpy(infos[size_t(k)].name, kNames[n][k], sizeof(infos[size_t(k)].name) - 1);
    }
    EXRImage exr;
    InitEXRImage(&exr);
    exr.num_channels = n;
    exr.images = planePointers.data();
    exr.width = image.width;
    exr.height = image.height;
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = n;
    header.channels = infos.data();
    header.pixel_types = types.data();
    header.requested_pixel_types = types.data();
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    const char* err = nullptr;
    // The header points into this function's vectors: nothing of it is freed by tinyexr here.
    if (SaveEXRImageToFile(&exr, &header, path.c_str(), &err) != TINYEXR_SUCCESS) {
        const std::string reason = err ? err : "unknown tinyexr error";
        if (err) FreeEXRErrorMessage(err);
        throw Error(str("writing '", path, "' failed: ", reason));
    }
}

void write(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels)
        throw Error(str("cannot write '", path, "': malformed image ", image.width, "x", image.height, "x",
                        image.channels));
    const std::string ext = extensionOf(path);
    if (ext == ".exr") return writeExr(path, image);
    int ok = 0;
    if (ext == ".hdr") {
        ok = stbi_write_hdr(path.c_str(), image.width, image.height, image.channels, image.pixels.data());
    } else {
        std::vector<std::uint8_t> bytes(image.pixels.size());
        for (size_t i = 0; i < bytes.size(); ++i)
            bytes[i] = std::uint8_t(std::lround(std::clamp(image.pixels[i], 0.0f, 1.0f) * 255.0f));
        const int stride = image.width * image.channels;
        if (ext == ".png")
            ok = stbi_write_png(path.c_str(), image.width, image.height, image.channels, bytes.data(), stride);
        else if (ext == ".jpg" || ext == ".jpeg")
            ok = stbi_write_jpg(path.c_str(), image.width, image.height, image.channels, bytes.data(), 85);
        else if (ext == ".bmp")
            ok = stbi_write_bmp(path.c_str(), image.width, image.height, image.channels, bytes.data());
        else if (ext == ".tga")
            ok = stbi_write_tga(path.c_str(), image.width, image.height, image.channels, bytes.data());
        else
            throw Error(str("cannot write '", path, "': the light image codec writes .png, .jpg, .bmp, .tga, .hdr "
                            "and .exr, not '", ext, "'"));
    }
    if (!ok) throw Error(str("writing '", path, "' failed (a folder that does not exist, or no space?)"));
}

} // namespace

const ImageCodec& lightImageCodec() {
    static const ImageCodec codec{"stb + tinyexr", &read, &readSize, &write};
    return codec;
}

} // namespace hfx
