// A surface from files: the device derives the same normals as the CPU twin of the Sobel kernel,
// and a bad file is refused without leaving anything behind.

#include "support/Fields.h"
#include "support/References.h"
#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/effects/ImageSurface.h"

#include <OpenImageIO/imageio.h>

#include <fstream>

namespace hfx::test {
namespace {

class ImageSurfaceTest : public DeviceTest {};

/// Writes heights (row 0 = bottom) as a 16-bit grey PNG, top row first as files store them.
std::string writeHeightMap(const std::string& name, const std::vector<float>& heights, int size) {
    const std::string path = outputPath(name);
    std::vector<float> rows(heights.size());
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) rows[size_t(size - 1 - y) * size + x] = heights[size_t(y) * size + x];
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(size, size, 1, OIIO::TypeDesc::UINT16)));
    out->write_image(OIIO::TypeDesc::FLOAT, rows.data());
    out->close();
    return path;
}

TEST_F(ImageSurfaceTest, DerivedNormalsMatchTheCpuSobel) {
    constexpr int N = 64;
    const auto heights = sumOfSines(N, {{0.3, 1, 2, 0.5}, {0.1, 3, -1, 0.0}});
    const std::string path = writeHeightMap("surface_height.png", heights, N);
    const float depthScale = 0.07f;
    ImageSurface surface(cl(), {.heightMap = path, .material = {.depthScale = depthScale}, .surface = {.mipmaps = false}});
    std::vector<float> gpu(size_t(N) * N * 4);
    glGetTextureImage(surface.textures().surface(), 0, GL_RGBA, GL_FLOAT, GLsizei(gpu.size() * 4), gpu.data());
    // The file stores 16 bits: compare with the CPU Sobel of the quantised heights.
    std::vector<float> quantised(heights.size());
    for (size_t i = 0; i < heights.size(); ++i) quantised[i] = std::round(heights[i] * 65535.0f) / 65535.0f;
    const auto cpu = sobelReference(quantised, N, depthScale);
    double maxDiff = 0;
    for (size_t i = 0; i < gpu.size(); ++i) maxDiff = std::max(maxDiff, double(std::abs(gpu[i] - cpu[i])));
    EXPECT_LT(maxDiff, 1e-5);
}

TEST_F(ImageSurfaceTest, BadFilesAreRefusedWithTheirNames) {
    const std::string good = writeHeightMap("good_height.png", sumOfSines(16, {{0.2, 1, 1, 0}}), 16);
    const std::string corrupt = outputPath("corrupt_height.png");
    std::ofstream(corrupt, std::ios::binary) << "not an image";
    const std::string otherSize = writeHeightMap("other_size.png", sumOfSines(8, {{0.2, 1, 1, 0}}), 8);
    struct Case {
        ImageSurfaceConfig config;
        std::string expected;
    };
    for (const Case& c : {Case{{.heightMap = "/missing/h.png"}, "/missing/h.png"},
                          Case{{.heightMap = corrupt}, corrupt},
                          Case{{.heightMap = good, .colorMap = otherSize}, otherSize},
                          Case{{.heightMap = good, .normalMap = otherSize}, otherSize},
                          Case{{.heightMap = ""}, "heightMap"}}) {
        try {
            ImageSurface surface(cl(), c.config);
            ADD_FAILURE() << "accepted " << c.expected;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos) << e.what();
        }
    }
}

} // namespace
} // namespace hfx::test
