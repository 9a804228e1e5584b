// The demo program as a user runs it: headless frames, determinism, and its errors.

#include "support/Fixtures.h"

#include "hfx/core/Image.h"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace hfx::test {
namespace {

struct Result {
    int exitCode;
    std::string output;
};

Result runDemo(const std::string& arguments, const std::string& prefix = "env -u DISPLAY -u WAYLAND_DISPLAY") {
    // One log per test and call: CTest runs the tests of this file in parallel processes.
    static int call = 0;
    const std::string log = outputPath(std::string("demo_") +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                                       "_" + std::to_string(call++) + ".txt");
    // By default no DISPLAY: the demo must fall back to headless by itself.
    const std::string command =
        prefix + " '" HFX_DEMO_EXECUTABLE "' " + arguments + " > '" + log + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), text.str()};
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

double luminanceStdDev(const Image& image) {
    double sum = 0, sum2 = 0;
    const size_t n = size_t(image.width) * image.height;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double l = 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
            sum += l;
            sum2 += l * l;
        }
    return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
}

TEST(Demo, HeadlessRunsAreDeterministicAndNotFlat) {
    const std::string args = "water --headless --frames 3 --width 320 --height 180 --field 128 --out ";
    const std::string a = outputPath("demo_a"), b = outputPath("demo_b");
    std::filesystem::remove_all(a);
    std::filesystem::remove_all(b);
    const Result first = runDemo(args + a);
    ASSERT_EQ(first.exitCode, 0) << first.output;
    const Result second = runDemo(args + b);
    ASSERT_EQ(second.exitCode, 0) << second.output;
    for (const char* frame : {"water_0000.png", "water_0001.png", "water_0002.png"}) {
        const std::string pa = a + "/" + frame, pb = b + "/" + frame;
        ASSERT_TRUE(std::filesystem::exists(pa)) << pa << "\n" << first.output;
        EXPECT_EQ(readBytes(pa), readBytes(pb)) << frame << " differs between identical runs";
        const Image image = readImage(pa);
        EXPECT_EQ(image.width, 320);
        EXPECT_GT(luminanceStdDev(image), 0.02) << frame << " is flat";
    }
    // The field is dynamic: frames differ.
    EXPECT_NE(readBytes(a + "/water_0000.png"), readBytes(a + "/water_0002.png"));
}

TEST(Demo, OpensAWindowUnderXvfb) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
    const std::string out = outputPath("demo_window");
    std::filesystem::remove_all(out);
    const Result r = runDemo("water --frames 3 --width 320 --height 180 --field 64 --out " + out,
                             "xvfb-run -a -s '-screen 0 640x480x24'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("hfx-demo: window"), std::string::npos) << r.output;
    EXPECT_GT(luminanceStdDev(readImage(out + "/water_0002.png")), 0.02);
}

TEST(Demo, UnknownSceneIsAClearError) {
    const Result r = runDemo("volcano --headless");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("unknown scene 'volcano'"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos);
}

TEST(Demo, MapsSceneRendersAFileAndRefusesBadOnes) {
    // A 16-bit height map made here: raised blocks.
    constexpr int N = 64;
    Image map{N, N, 1, std::vector<float>(N * N)};
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) map.at(x, y, 0) = (x % 16 < 2 || y % 16 < 2) ? 0.1f : 0.9f;
    const std::string heightMap = outputPath("demo_height.exr");
    writeImage(heightMap, map);
    const std::string out = outputPath("demo_maps");
    const Result ok = runDemo("maps --headless --width 160 --height 90 --height-map " + heightMap + " --out " + out);
    ASSERT_EQ(ok.exitCode, 0) << ok.output;
    EXPECT_GT(luminanceStdDev(readImage(out + "/maps_0000.png")), 0.02);

    const Result missing = runDemo("maps --headless --height-map /no/such/height.png");
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_NE(missing.output.find("/no/such/height.png"), std::string::npos) << missing.output;

    const std::string corrupt = outputPath("demo_corrupt.png");
    std::ofstream(corrupt, std::ios::binary) << "\x89PNG\r\n\x1a\n garbage";
    const Result bad = runDemo("maps --headless --height-map " + corrupt);
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find(corrupt), std::string::npos) << bad.output;

    const Result none = runDemo("maps --headless");
    EXPECT_NE(none.exitCode, 0);
    EXPECT_NE(none.output.find("--height-map"), std::string::npos) << none.output;
}

TEST(Demo, BadOptionValuesAreClearErrors) {
    for (const char* args : {"water --field 0", "water --technique raytrace", "water --frames -3",
                             "water --samples-min 40 --samples-max 10", "water --width abc"}) {
        const Result r = runDemo(std::string(args) + " --headless");
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_FALSE(r.output.empty()) << args << " printed nothing";
    }
    const Result r = runDemo("water --technique raytrace --headless");
    EXPECT_NE(r.output.find("raytrace"), std::string::npos) << r.output;
}

TEST(Demo, HelpListsTheOptions) {
    const Result r = runDemo("--help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* option : {"--headless", "--frames", "--out", "--field", "--technique",
                               "--samples-min", "--samples-max", "--depth-scale", "--seed"})
        EXPECT_NE(r.output.find(option), std::string::npos) << option;
}

} // namespace
} // namespace hfx::test
