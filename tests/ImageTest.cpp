#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/tools/ImageFiles.h"

#include <cmath>

#if defined(HFX_WITH_OPENIMAGEIO)
#include <OpenImageIO/imageio.h>
#endif

#include <filesystem>
#include <fstream>

namespace hfx::test {
namespace {

// Every codec this build has (OpenImageIO where built with it, the light one always) is held to
// the same behaviour; files written by one are read by the other.
std::vector<const ImageCodec*> codecs() {
    std::vector<const ImageCodec*> all{&lightImageCodec()};
    if (openImageIoCodec()) all.push_back(openImageIoCodec());
    return all;
}

class ImageFilesTest : public ::testing::TestWithParam<const ImageCodec*> {
protected:
    const ImageCodec& codec() const { return *GetParam(); }
    std::string tag() const { return GetParam() == &lightImageCodec() ? "light" : "oiio"; }
    std::string path(const std::string& name) const { return outputPath("image_" + tag() + "_" + name); }
    std::string messageOf(const std::string& file, const ImageReadLimits& limits = {}) const {
        try {
            codec().read(file, limits);
        } catch (const Error& e) {
            return e.what();
        }
        return "no error";
    }
};

/// A w x h image of `channels`, values (x + y + c) / (w + h + 4).
Image ramp(int w, int h, int channels) {
    Image image{w, h, channels, std::vector<float>(size_t(w) * h * channels)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) image.at(x, y, c) = float(x + y + c) / float(w + h + 4);
    return image;
}

#if defined(HFX_WITH_OPENIMAGEIO)
/// The ramp written by OpenImageIO itself in `format` (16-bit integers, TIFF: what the light
/// codec cannot write).
std::string writeWithOiio(const std::string& path, int w, int h, int channels, OIIO::TypeDesc format) {
    const Image image = ramp(w, h, channels);
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(w, h, channels, format)));
    out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
    out->close();
    return path;
}
#endif

long peakResidentKiB() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
    return 0;
}

TEST_P(ImageFilesTest, FormatsAndChannelCounts) {
    struct Case {
        std::string file;
        int channels;
        float tolerance; // quantisation of the stored format
    };
    std::vector<Case> cases;
    // Written by the light codec: 8-bit PNG with 1 to 4 channels, float EXR with 1, 3 and 4.
    for (int channels : {1, 2, 3, 4}) {
        const std::string file = path(str("w", channels, ".png"));
        lightImageCodec().write(file, ramp(37, 21, channels));
        cases.push_back({file, channels, 0.5f / 255});
    }
    for (int channels : {1, 3, 4}) {
        const std::string file = path(str("w", channels, ".exr"));
        lightImageCodec().write(file, ramp(37, 21, channels));
        cases.push_back({file, channels, 0.0f});
    }
#if defined(HFX_WITH_OPENIMAGEIO)
    // Written by OpenImageIO: 16-bit PNG and float EXR for both codecs, TIFF for itself.
    cases.push_back({writeWithOiio(path("rgb16.png"), 37, 21, 3, OIIO::TypeDesc::UINT16), 3, 0.5f / 65535});
    cases.push_back({writeWithOiio(path("g32.exr"), 37, 21, 1, OIIO::TypeDesc::FLOAT), 1, 0.0f});
    cases.push_back({writeWithOiio(path("rgba32.exr"), 37, 21, 4, OIIO::TypeDesc::FLOAT), 4, 0.0f});
    if (&codec() == openImageIoCodec()) {
        cases.push_back({writeWithOiio(path("rgba16.tif"), 37, 21, 4, OIIO::TypeDesc::UINT16), 4, 0.5f / 65535});
        cases.push_back({writeWithOiio(path("rgba32.tif"), 37, 21, 4, OIIO::TypeDesc::FLOAT), 4, 0.0f});
    }
#endif
    for (const Case& c : cases) {
        const ImageSize size = codec().readSize(c.file, {});
        EXPECT_EQ(size.width, 37) << c.file;
        EXPECT_EQ(size.channels, c.channels) << c.file;
        const Image image = codec().read(c.file, {});
        ASSERT_EQ(image.width, 37) << c.file;
        ASSERT_EQ(image.height, 21) << c.file;
        ASSERT_EQ(image.channels, c.channels) << c.file;
        for (int k = 0; k < c.channels; ++k)
            EXPECT_NEAR(image.at(30, 20, k), float(30 + 20 + k) / (37 + 21 + 4), c.tolerance + 1e-7f)
                << c.file << " channel " << k;
    }
}

TEST_P(ImageFilesTest, WriteThenReadRoundTripsAndTheOtherCodecReadsItToo) {
    Image image{8, 4, 3, std::vector<float>(8 * 4 * 3)};
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 17) / 16.0f;
    codec().write(path("roundtrip.exr"), image);
    codec().write(path("roundtrip.png"), image);
    for (const ImageCodec* reader : codecs()) {
        const Image exr = reader->read(path("roundtrip.exr"), {});
        const Image png = reader->read(path("roundtrip.png"), {});
        ASSERT_EQ(exr.pixels.size(), image.pixels.size()) << reader->name;
        ASSERT_EQ(png.pixels.size(), image.pixels.size()) << reader->name;
        for (size_t i = 0; i < image.pixels.size(); ++i) {
            EXPECT_EQ(exr.pixels[i], image.pixels[i]) << reader->name << " at " << i;
            EXPECT_NEAR(png.pixels[i], image.pixels[i], 0.5 / 255 + 1e-6) << reader->name;
        }
    }
}

TEST_P(ImageFilesTest, MissingFileNamesThePath) {
    const std::string message = messageOf("/nonexistent/height.png");
    EXPECT_NE(message.find("/nonexistent/height.png"), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST_P(ImageFilesTest, CorruptFileIsRefused) {
    const std::string file = path("corrupt.png");
    std::ofstream(file, std::ios::binary) << "\x89PNG\r\n\x1a\n this is not a png at all";
    const std::string message = messageOf(file);
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_EQ(message.find("no error"), std::string::npos);
}

TEST_P(ImageFilesTest, TruncatedFileIsRefused) {
    const std::string whole = path("whole.png");
    Image noise{64, 64, 3, std::vector<float>(64 * 64 * 3)};
    for (size_t i = 0; i < noise.pixels.size(); ++i) noise.pixels[i] = float((i * 7919) % 251) / 250.0f;
    lightImageCodec().write(whole, noise);
    for (const char* ext : {".png", ".exr"}) {
        const std::string full = path(str("whole", ext));
        lightImageCodec().write(full, noise);
        const std::string cut = path(str("truncated", ext));
        std::filesystem::copy_file(full, cut, std::filesystem::copy_options::overwrite_existing);
        std::filesystem::resize_file(cut, std::filesystem::file_size(full) / 2);
        const std::string message = messageOf(cut);
        EXPECT_NE(message.find(cut), std::string::npos) << message;
    }
}

TEST_P(ImageFilesTest, OversizedImageIsRefusedBeforeReading) {
    for (const char* ext : {".png", ".exr"}) {
        const std::string file = path(str("big", ext));
        lightImageCodec().write(file, ramp(300, 200, 1));
        const std::string message = messageOf(file, {.maxPixels = 1000});
        EXPECT_NE(message.find("300x200"), std::string::npos) << message;
    }
}

TEST_P(ImageFilesTest, NonFiniteFloatsAreRefused) {
    Image image{2, 2, 1, {0.0f, NAN, 0.5f, 1.0f}};
    codec().write(path("nan.exr"), image);
    const std::string message = messageOf(path("nan.exr"));
    EXPECT_NE(message.find("NaN"), std::string::npos) << message;
}

TEST_P(ImageFilesTest, ExrHeaderClaimingAHugeImageIsRefusedWithoutAllocatingForIt) {
    // Found by scripts/fuzz.sh: an EXR header whose windows made the reader allocate about 2 GB
    // while opening, before any size check of ours could run. The readers now get the limits.
    static const unsigned char bytes[] = {
    0x76, 0x2f, 0x31, 0x01, 0x02, 0x00, 0x00, 0x00, 0x63, 0x61, 0x70, 0x44, 0x61, 0x74, 0x65, 0x00,
    0x73, 0x74, 0x72, 0x69, 0x6e, 0x67, 0x00, 0x13, 0x00, 0x6e, 0x65, 0x4f, 0x72, 0x64, 0x65, 0x72,
    0x00, 0x6c, 0x69, 0x6e, 0x65, 0x4f, 0x72, 0x64, 0x65, 0x72, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00,
    0x70, 0x69, 0x78, 0x65, 0x6c, 0x41, 0x73, 0x70, 0x65, 0x63, 0x74, 0x52, 0x61, 0x74, 0x69, 0x6f,
    0x00, 0x66, 0x6c, 0x6f, 0x61, 0x74, 0x00, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, 0x73,
    0x63, 0x72, 0x65, 0x65, 0x6e, 0x57, 0x69, 0x6e, 0x64, 0x6f, 0x77, 0x43, 0x65, 0x6e, 0x74, 0x65,
    0x72, 0x00, 0x76, 0x32, 0x66, 0x00, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x73, 0x63, 0x72, 0x65, 0x65, 0x6e, 0x57, 0x69, 0x6e, 0x64, 0x6f, 0x77, 0x57, 0x69,
    0x64, 0x74, 0x68, 0x00, 0x66, 0x6c, 0x6f, 0x61, 0x74, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x09, 0x00, 0x00, 0x00, 0x05, 0x00, 0x00, 0x00, 0x64, 0x69, 0x73, 0x70, 0x6c, 0x61, 0x79, 0x57,
    0x69, 0x6e, 0x64, 0x6f, 0x77, 0x00, 0x62, 0x6f, 0x78, 0x32, 0x69, 0x00, 0x10, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x09, 0x00, 0x00, 0x00, 0x05, 0x00, 0x00, 0x00,
    0x6c, 0x69, 0x6e, 0x65, 0x4f, 0x72, 0x64, 0x65, 0x72, 0x00, 0x6c, 0x69, 0x6e, 0x65, 0x4f, 0x72,
    0x64, 0x65, 0x72, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x70, 0x69, 0x78, 0x65, 0x6c, 0x41, 0x73,
    0x70, 0x65, 0x63, 0x74, 0x52, 0x61, 0x74, 0x69, 0x6f, 0x00, 0x66, 0x6c, 0x6f, 0x61, 0x74, 0x00,
    0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, 0x73, 0x63, 0x72, 0x65, 0x65, 0x6e, 0x57, 0x69,
    0x6e, 0x64, 0x6f, 0x77, 0x43, 0x65, 0x6e, 0x74, 0x65, 0x72, 0x00, 0x76, 0x32, 0x66, 0x00, 0x08,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x73, 0x63, 0x72, 0x65, 0x65,
    0x6e, 0x57, 0x69, 0x6e, 0x64, 0x6f, 0x77, 0x57, 0x69, 0x64, 0x74, 0x68, 0x00, 0x66, 0x6c, 0x6f,
    0x61, 0x74, 0x00, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, 0x00, 0x43, 0x01, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x5e, 0x00, 0x00, 0x00, 0x78, 0x5e, 0x63, 0x98,
    0x30, 0x5d, 0xe6, 0xbc, 0xfe, 0xf4, 0xc6, 0x49, 0x8b, 0x7b, 0x26, 0x08, 0x9d, 0x54, 0x9e, 0xba,
    0x69, 0xce, 0xc4, 0xce, 0x76, 0xce, 0xc3, 0x62, 0xd3, 0x1e, 0xcd, 0xee, 0x68, 0xab, 0x63, 0xd8,
    0xc7, 0x35, 0x4d, 0x64, 0x46, 0x43, 0x53, 0xd9, 0xf7, 0x1d, 0x7f, 0x67, 0xb8, 0x4f, 0xae, 0xa8,
    0xcd, 0x7b, 0xb7, 0xf9, 0xe3, 0xcc, 0x9a, 0xde, 0xfc, 0xca, 0xd4, 0xa7, 0x6b, 0x9f, 0xf7, 0x35,
    0x35, 0xd6, 0xd7, 0xd7, 0x54, 0xd7, 0xb5, 0xb6, 0x42, 0x19, 0x6d, 0x2d, 0x40, 0x46, 0x5d, 0x6d,
    0x75, 0x7d, 0x2b, 0x41, 0x06, 0x00, 0x83, 0x11, 0x3d, 0xb6};
    const std::string file = path("huge_header.exr");
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes), sizeof bytes);
    const long before = peakResidentKiB();
    EXPECT_THROW(codec().read(file, {}), Error);
    EXPECT_LT(peakResidentKiB() - before, 256 * 1024) << "the reader allocated for the claimed size";
}

TEST_P(ImageFilesTest, MalformedImageOrUnknownFormatIsRefused) {
    EXPECT_THROW(codec().write(path("bad.png"), Image{4, 4, 3, {}}), Error);
    EXPECT_THROW(codec().write("/nonexistent/dir/x.png", Image{1, 1, 1, {0.5f}}), Error);
    EXPECT_THROW(codec().write("/nonexistent/dir/x.exr", Image{1, 1, 1, {0.5f}}), Error);
    if (&codec() == &lightImageCodec()) {
        const std::string m = hfx::test::messageOf([&] { codec().write(path("x.tif"), Image{1, 1, 1, {0.5f}}); });
        EXPECT_NE(m.find(".tif"), std::string::npos) << m;
    }
}

INSTANTIATE_TEST_SUITE_P(Codecs, ImageFilesTest, ::testing::ValuesIn(codecs()),
                         [](const auto& param) { return param.param == &lightImageCodec() ? "light" : "OpenImageIO"; });

} // namespace
} // namespace hfx::test
