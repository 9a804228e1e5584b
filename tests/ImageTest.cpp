#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Image.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <fstream>

namespace hfx::test {
namespace {

std::string messageOf(const std::string& path, const ImageReadLimits& limits = {}) {
    try {
        readImage(path, limits);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

/// Writes a w x h image of `channels` with OIIO in `format`, values (x + y) / (w + h).
std::string writeTestImage(const std::string& name, int w, int h, int channels, OIIO::TypeDesc format) {
    const std::string path = outputPath(name);
    std::vector<float> pixels(size_t(w) * h * channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                pixels[(size_t(y) * w + x) * channels + c] = float(x + y + c) / float(w + h + 4);
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(w, h, channels, format)));
    out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
    out->close();
    return path;
}

TEST(ImageRead, FormatsAndChannelCounts) {
    struct Case {
        const char* name;
        int channels;
        OIIO::TypeDesc format;
        float tolerance; // quantisation of the stored format
    };
    for (const Case& c : {Case{"g8.png", 1, OIIO::TypeDesc::UINT8, 0.5f / 255},
                         Case{"ga8.png", 2, OIIO::TypeDesc::UINT8, 0.5f / 255},
                         Case{"rgb16.png", 3, OIIO::TypeDesc::UINT16, 0.5f / 65535},
                         Case{"rgba16.tif", 4, OIIO::TypeDesc::UINT16, 0.5f / 65535},
                         Case{"g32.exr", 1, OIIO::TypeDesc::FLOAT, 0.0f},
                         Case{"rgba32.tif", 4, OIIO::TypeDesc::FLOAT, 0.0f}}) {
        const std::string path = writeTestImage(c.name, 37, 21, c.channels, c.format);
        const Image image = readImage(path);
        ASSERT_EQ(image.width, 37) << c.name;
        ASSERT_EQ(image.height, 21) << c.name;
        ASSERT_EQ(image.channels, c.channels) << c.name;
        EXPECT_NEAR(image.at(30, 20, c.channels - 1), float(30 + 20 + c.channels - 1) / (37 + 21 + 4),
                    c.tolerance + 1e-7f)
            << c.name;
    }
}

TEST(ImageRead, WriteThenReadRoundTrips) {
    Image image{8, 4, 3, std::vector<float>(8 * 4 * 3)};
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 17) / 16.0f;
    writeImage(outputPath("roundtrip.exr"), image);
    writeImage(outputPath("roundtrip.png"), image);
    const Image exr = readImage(outputPath("roundtrip.exr"));
    const Image png = readImage(outputPath("roundtrip.png"));
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        EXPECT_EQ(exr.pixels[i], image.pixels[i]);
        EXPECT_NEAR(png.pixels[i], image.pixels[i], 0.5 / 255 + 1e-6);
    }
}

TEST(ImageRead, MissingFileNamesThePath) {
    const std::string message = messageOf("/nonexistent/height.png");
    EXPECT_NE(message.find("/nonexistent/height.png"), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST(ImageRead, CorruptFileIsRefused) {
    const std::string path = outputPath("corrupt.png");
    std::ofstream(path, std::ios::binary) << "\x89PNG\r\n\x1a\n this is not a png at all";
    const std::string message = messageOf(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_EQ(message.find("no error"), std::string::npos);
}

TEST(ImageRead, TruncatedFileIsRefused) {
    const std::string whole = writeTestImage("whole.png", 64, 64, 3, OIIO::TypeDesc::UINT8);
    const std::string cut = outputPath("truncated.png");
    std::filesystem::copy_file(whole, cut, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::resize_file(cut, std::filesystem::file_size(whole) / 2);
    const std::string message = messageOf(cut);
    EXPECT_NE(message.find(cut), std::string::npos) << message;
}

TEST(ImageRead, OversizedImageIsRefusedBeforeReading) {
    const std::string path = writeTestImage("big.png", 300, 200, 1, OIIO::TypeDesc::UINT8);
    const std::string message = messageOf(path, {.maxPixels = 1000});
    EXPECT_NE(message.find("300x200"), std::string::npos) << message;
}

TEST(ImageRead, NonFiniteFloatsAreRefused) {
    Image image{2, 2, 1, {0.0f, NAN, 0.5f, 1.0f}};
    writeImage(outputPath("nan.exr"), image);
    const std::string message = messageOf(outputPath("nan.exr"));
    EXPECT_NE(message.find("NaN"), std::string::npos) << message;
}

TEST(ImageWrite, MalformedImageIsRefused) {
    EXPECT_THROW(writeImage(outputPath("bad.png"), Image{4, 4, 3, {}}), Error);
    EXPECT_THROW(writeImage("/nonexistent/dir/x.png", Image{1, 1, 1, {0.5f}}), Error);
}

} // namespace
} // namespace hfx::test
