#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/SurfaceMaps.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hfx::test {
namespace {

TEST(SurfaceMaps, HeightsAreFlippedSoRowZeroIsTheBottom) {
    const Image image{2, 3, 1, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f}}; // top row first
    const auto h = heightsFromImage(image, "h.png");
    ASSERT_EQ(h.size(), 6u);
    EXPECT_EQ(h[0], 0.5f); // bottom-left of the image
    EXPECT_EQ(h[5], 0.2f); // top-right
}

TEST(SurfaceMaps, OutOfRangeHeightsAreRefusedNamingFileAndPixel) {
    const Image image{2, 1, 1, {0.5f, 1.5f}};
    const std::string message = messageOf([&] { heightsFromImage(image, "terrain.exr"); });
    EXPECT_NE(message.find("terrain.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("(1, 0)"), std::string::npos) << message;
}

TEST(SurfaceMaps, NormalMapDecodesAndRenormalises) {
    // (0.5, 0.5, 1) encodes (0, 0, 1); (1, 0.5, 0.5) encodes (1, 0, 0) with z = 0.
    const Image normals{2, 1, 3, {0.5f, 0.5f, 1.0f, 0.75f, 0.5f, 0.75f}};
    const auto packed = packNormalMap(normals, "n.png", {0.25f, 0.75f});
    EXPECT_NEAR(packed[2], 1.0f, 1e-6);
    EXPECT_NEAR(packed[4], std::sqrt(0.5f), 1e-6);
    EXPECT_NEAR(packed[6], std::sqrt(0.5f), 1e-6);
    EXPECT_EQ(packed[3], 0.25f);
    EXPECT_EQ(packed[7], 0.75f);
}

TEST(SurfaceMaps, BadNormalMapsAreRefused) {
    const std::vector<float> heights(4, 0.5f);
    EXPECT_NE(messageOf([&] { packNormalMap(Image{2, 2, 1, std::vector<float>(4, 0.5f)}, "gray.png", heights); })
                  .find("gray.png"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { packNormalMap(Image{3, 1, 3, std::vector<float>(9, 0.5f)}, "size.png", heights); })
                  .find("does not match"),
              std::string::npos);
    Image downwards{2, 2, 3, std::vector<float>(12, 0.5f)};
    for (int i = 2; i < 12; i += 3) downwards.pixels[i] = 1.0f; // all (0, 0, 1) ...
    downwards.at(1, 1, 2) = 0.0f;                               // ... but one (0, 0, -1)
    EXPECT_NE(messageOf([&] { packNormalMap(downwards, "down.png", heights); }).find("(1, 1)"),
              std::string::npos);
}

} // namespace
} // namespace hfx::test
