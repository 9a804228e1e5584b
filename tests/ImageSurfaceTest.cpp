// A surface from files: the device derives the same normals as the CPU twin of the Sobel kernel,
// and a bad file is refused without leaving anything behind.

#include "support/Fields.h"
#include "support/References.h"
#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/effects/ImageSurface.h"

#include <fstream>

namespace hfx::test {
namespace {

class ImageSurfaceTest : public DeviceTest {};

/// Writes heights (row 0 = bottom) as a grey image (8-bit PNG or float EXR, by the name's
/// extension), top row first as files store them.
std::string writeHeightMap(const std::string& name, const std::vector<float>& heights, int size) {
    const std::string path = outputPath(name);
    Image rows{size, size, 1, std::vector<float>(heights.size())};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) rows.at(x, size - 1 - y, 0) = heights[size_t(y) * size + x];
    writeImage(path, rows);
    return path;
}

TEST_F(ImageSurfaceTest, DerivedNormalsMatchTheCpuSobel) {
    constexpr int N = 64;
    const auto heights = sumOfSines(N, {{0.3, 1, 2, 0.5}, {0.1, 3, -1, 0.0}});
    const std::string path = writeHeightMap("surface_height.exr", heights, N);
    const float depthScale = 0.07f;
    ImageSurface surface(cl(), {.maps = readSurfaceMaps(path, "", ""), .material = {.depthScale = depthScale},
                                .surface = {.mipmaps = false, .format = SurfaceFormat::Float32}});
    std::vector<float> gpu(size_t(N) * N * 4);
    glGetTextureImage(surface.textures().surface(), 0, GL_RGBA, GL_FLOAT, GLsizei(gpu.size() * 4), gpu.data());
    // The file stores 32-bit floats: the CPU Sobel of the same heights.
    const auto cpu = sobelReference(heights, N, depthScale);
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
        std::string height, normal, color, expected;
    };
    // The files, by the tools' reader.
    for (const Case& c : {Case{"/missing/h.png", "", "", "/missing/h.png"}, Case{corrupt, "", "", corrupt},
                          Case{good, "", otherSize, otherSize}, Case{good, otherSize, "", otherSize}}) {
        const std::string m = messageOf([&] { readSurfaceMaps(c.height, c.normal, c.color); });
        EXPECT_NE(m.find(c.expected), std::string::npos) << m;
    }
    // The maps themselves, by the effect: no heights, or parts that do not fit them.
    SurfaceMaps maps = readSurfaceMaps(good, "", "");
    EXPECT_NE(messageOf([&] { ImageSurface(cl(), {}); }).find("heights"), std::string::npos);
    SurfaceMaps shortNormals = maps;
    shortNormals.normals.assign(12, 0.0f);
    EXPECT_NE(messageOf([&] { ImageSurface(cl(), {.maps = shortNormals}); }).find("normals"), std::string::npos);
    SurfaceMaps high = maps;
    high.heights[5] = 1.5f;
    EXPECT_NE(messageOf([&] { ImageSurface(cl(), {.maps = high}); }).find("1.5"), std::string::npos);
    ImageSurface fine(cl(), {.maps = maps}); // and the good one is taken
    EXPECT_EQ(fine.textures().config().width, 16);
}

} // namespace
} // namespace hfx::test
