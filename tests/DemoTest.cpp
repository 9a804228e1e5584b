// The demo program as a user runs it: headless frames, determinism, and its errors.

#include "support/Fixtures.h"

#include "hfx/tools/ImageFiles.h"
#include "hfx/core/Camera.h"
#include "hfx/effects/Technique.h"

#include <glm/trigonometric.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

namespace hfx::test {
namespace {

struct Result {
    int exitCode;
    std::string output;
};

Result runDemo(const std::string& arguments, const std::string& prefix = "env -u DISPLAY -u WAYLAND_DISPLAY") {
    // One log per test and call: CTest runs the tests of this file in parallel processes.
    static int call = 0;
    std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(test.begin(), test.end(), '/', '_'); // parameterised names
    const std::string log = outputPath("demo_" + test + "_" + std::to_string(call++) + ".txt");
    // By default no DISPLAY: the demo must fall back to headless by itself.
    const std::string command =
        prefix + " '" HFX_DEMO_EXECUTABLE "' " + arguments + " > '" + log + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), text.str()};
}

/// The second frame of a flat scene drawn at 320x180 from a field x field heights (128² unless
/// asked) with `flags`, rendered into a fresh folder named by `tag` and the scene; the run's
/// output into `log` where one is given.
Image flatSceneFrame(const std::string& scene, const std::string& tag, const std::string& flags, int field = 128,
                     std::string* log = nullptr) {
    const std::string dir = outputPath("demo_" + tag + "_" + scene);
    std::filesystem::remove_all(dir);
    const Result r = runDemo(scene + " --headless --frames 2 --width 320 --height 180 --field " + std::to_string(field) +
                             " --out " + dir + flags);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    if (log) *log = r.output;
    return readImage(dir + "/" + scene + "_0001.png");
}

/// How far apart two frames of one size are: per pixel the largest difference of its three
/// colour channels in 0..255 levels; their mean and the share of pixels more than 16 levels apart.
struct FrameDifference {
    double mean = 0, far = 0;
};
FrameDifference frameDifference(const Image& x, const Image& y) {
    double sum = 0;
    size_t far = 0;
    const size_t n = x.pixels.size() / size_t(x.channels);
    for (size_t p = 0; p < n; ++p) {
        double d = 0;
        for (int k = 0; k < std::min(x.channels, 3); ++k)
            d = std::max(d, 255.0 * std::abs(double(x.pixels[p * size_t(x.channels) + size_t(k)]) -
                                             y.pixels[p * size_t(y.channels) + size_t(k)]));
        sum += d;
        far += d > 16.0;
    }
    return {sum / double(n), double(far) / double(n)};
}

/// The second and third of three half-second frames of `scene` at 320x180 with `flags`, written
/// to a folder of their own (`tag`), and the run's log.
struct HalfSecondFrames {
    Image second, third;
    std::string log;
};
HalfSecondFrames halfSecondFrames(const std::string& scene, const std::string& tag, const std::string& flags) {
    const std::string dir = outputPath("demo_" + tag + "_" + scene);
    std::filesystem::remove_all(dir);
    const Result r = runDemo(scene + " --headless --frames 3 --dt 0.5 --width 320 --height 180 --field 128 --out " +
                             dir + flags);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return {readImage(dir + "/" + scene + "_0001.png"), readImage(dir + "/" + scene + "_0002.png"), r.output};
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

/// The first frame of `scene args` at width x height, written into a fresh folder named by `tag`,
/// and where the world point `point` falls in it (pixels from the top-left corner, a pixel's
/// centre at +0.5) through `camera`, the orbit camera the run's options place.
struct SeenPoint {
    Image frame;
    glm::dvec2 pixel;
};
SeenPoint renderAndFind(const std::string& tag, const std::string& args, int width, int height, Camera camera,
                        glm::vec3 point) {
    const std::string dir = outputPath("demo_" + tag);
    std::filesystem::remove_all(dir);
    const std::string scene = args.substr(0, args.find(' '));
    const Result r = runDemo(args + " --headless --frames 1 --width " + std::to_string(width) + " --height " +
                             std::to_string(height) + " --out " + dir);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    camera.aspect = float(width) / float(height);
    const glm::vec4 clip = camera.viewProjection() * glm::vec4(point, 1.0f);
    return {readImage(dir + "/" + scene + "_0000.png"),
            {(clip.x / clip.w * 0.5 + 0.5) * width, (0.5 - clip.y / clip.w * 0.5) * height}};
}

class DemoScenes : public ::testing::TestWithParam<const char*> {};

TEST_P(DemoScenes, HeadlessRunsAreDeterministicDynamicAndFinite) {
    const std::string scene = GetParam();
    const std::string args = scene + " --headless --frames 3 --width 320 --height 180 --field 128 --out ";
    const std::string a = outputPath("demo_" + scene + "_a"), b = outputPath("demo_" + scene + "_b");
    const std::string maps = outputPath("demo_" + scene + "_maps");
    for (const auto& dir : {a, b, maps}) std::filesystem::remove_all(dir);
    const Result first = runDemo(args + a);
    ASSERT_EQ(first.exitCode, 0) << first.output;
    const Result second = runDemo(args + b + " --export-maps " + maps);
    ASSERT_EQ(second.exitCode, 0) << second.output;
    for (int frame = 0; frame < 3; ++frame) {
        const std::string name = scene + "_000" + std::to_string(frame) + ".png";
        const std::string pa = a + "/" + name, pb = b + "/" + name;
        ASSERT_TRUE(std::filesystem::exists(pa)) << pa << "\n" << first.output;
        EXPECT_EQ(readBytes(pa), readBytes(pb)) << name << " differs between identical runs";
        const Image image = readImage(pa);
        EXPECT_EQ(image.width, 320);
        EXPECT_GT(luminanceStdDev(image), 0.02) << name << " is flat";
    }
    // The field is dynamic: frames differ.
    EXPECT_NE(readBytes(a + "/" + scene + "_0000.png"), readBytes(a + "/" + scene + "_0002.png"));
    // The exported field: heights in [0,1] and unit normals, no NaN, as the renderer saw them.
    const Image height = readImage(maps + "/height.exr");
    const Image normal = readImage(maps + "/normal.exr");
    ASSERT_EQ(height.width, normal.width);
    double lo = 1.0, hi = 0.0;
    for (float h : height.pixels) {
        ASSERT_TRUE(h >= 0.0f && h <= 1.0f) << h;
        lo = std::min(lo, double(h));
        hi = std::max(hi, double(h));
    }
    EXPECT_GT(hi - lo, 0.05) << "the exported height field is flat";
    for (int y = 0; y < normal.height; ++y)
        for (int x = 0; x < normal.width; ++x) {
            const double len = std::hypot(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
            ASSERT_NEAR(len, 1.0, 1e-3) << x << "," << y;
        }
    for (const char* file : {"height.png", "normal.png", "albedo.png"})
        EXPECT_TRUE(std::filesystem::exists(maps + "/" + file)) << file;
}

INSTANTIATE_TEST_SUITE_P(Scenes, DemoScenes, ::testing::Values("water", "decals", "planet", "noise"));

TEST(Demo, SineWavesStillRender) {
    const std::string out = outputPath("demo_sine");
    const Result r = runDemo("water --waves sine --headless --width 160 --height 90 --field 64 --out " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_GT(luminanceStdDev(readImage(out + "/water_0000.png")), 0.02);
}

TEST(Demo, EveryTechniqueDrawsTheDecalWall) {
    for (const TechniqueInfo& info : kTechniqueTable) {
        const char* technique = info.name;
        const std::string out = outputPath(std::string("demo_technique_") + technique);
        const Result r = runDemo(std::string("decals --headless --frames 2 --width 160 --height 90 --field 128 --technique ") +
                                 technique + " --out " + out);
        ASSERT_EQ(r.exitCode, 0) << technique << "\n" << r.output;
        EXPECT_GT(luminanceStdDev(readImage(out + "/decals_0001.png")), 0.02) << technique;
    }
}

TEST(Demo, TheExactTracerIsTheDefaultWhereTheSurfaceCanCarryItsPyramid) {
    // One power-of-two grid in a float format: hier. The ocean's cascades, other sizes, 8-bit
    // storage and height maps of other sizes: pom. An explicit --technique wins.
    Image odd{48, 40, 1, std::vector<float>(48 * 40, 0.5f)};
    odd.pixels[100] = 0.9f;
    const std::string oddMap = outputPath("demo_auto_odd.exr");
    writeImage(oddMap, odd);
    Image square{64, 64, 1, std::vector<float>(64 * 64, 0.5f)};
    square.pixels[100] = 0.9f;
    const std::string squareMap = outputPath("demo_auto_square.exr");
    writeImage(squareMap, square);
    const std::string common = " --headless --frames 1 --width 96 --height 64 --out " + outputPath("demo_auto") + " ";
    for (const auto& [args, technique] :
         {std::pair{"decals --field 64", "hier"}, std::pair{"planet --field 64", "hier"}, std::pair{"noise --field 64", "hier"},
          std::pair{"water --field 64", "pom"}, std::pair{"decals --field 96", "pom"},
          std::pair{"decals --field 64 --surface-format unorm8", "pom"}, std::pair{"decals --field 64 --technique relief", "relief"}}) {
        const Result r = runDemo(std::string(args) + common);
        ASSERT_EQ(r.exitCode, 0) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(std::string("technique: ") + technique), std::string::npos) << args << "\n" << r.output;
    }
    for (const auto& [map, technique] : {std::pair{squareMap, "hier"}, std::pair{oddMap, "pom"}}) {
        const Result r = runDemo("maps --height-map " + map + common);
        ASSERT_EQ(r.exitCode, 0) << map << "\n" << r.output;
        EXPECT_NE(r.output.find(std::string("technique: ") + technique), std::string::npos) << map << "\n" << r.output;
    }
}

TEST(Demo, EverySurfaceFormatRendersAndUnorm8RefusesTheTracer) {
    for (const char* scene : {"water", "decals", "planet"})
        for (const char* format : {"float16", "unorm8"}) {
            const std::string out = outputPath(std::string("demo_format_") + scene + "_" + format);
            const Result r = runDemo(std::string(scene) + " --headless --frames 2 --width 160 --height 90 --field 64 " +
                                     "--surface-format " + format + " --out " + out);
            ASSERT_EQ(r.exitCode, 0) << scene << " " << format << "\n" << r.output;
            EXPECT_GT(luminanceStdDev(readImage(out + "/" + scene + "_0001.png")), 0.02) << scene << " " << format;
        }
    const Result r = runDemo("decals --headless --field 64 --technique hier --surface-format unorm8");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("float format"), std::string::npos) << r.output;
}

TEST(Demo, ShotListDrivesTheDecalsAndBadListsNameTheLine) {
    const std::string shots = outputPath("demo_shots.txt");
    std::ofstream(shots) << "# two bullets and a click, then an explosion\n"
                            "bullet 1 0.5 0.5\nbullet 1 1.5 1.5\nclick 2 160 90\nexplosion 2 1.0 1.0 5\n";
    const std::string a = outputPath("demo_shots_a"), none = outputPath("demo_shots_none");
    const std::string args = "decals --headless --frames 3 --width 320 --height 180 --field 128 --out ";
    const Result r = runDemo(args + a + " --shots " + shots);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // An empty list: the undamaged wall. The shots change what is drawn.
    const std::string empty = outputPath("demo_shots_empty.txt");
    std::ofstream(empty) << "# nothing\n";
    const Result clean = runDemo(args + none + " --shots " + empty);
    ASSERT_EQ(clean.exitCode, 0) << clean.output;
    EXPECT_EQ(readBytes(a + "/decals_0000.png"), readBytes(none + "/decals_0000.png")) << "frame 0 precedes any shot";
    EXPECT_NE(readBytes(a + "/decals_0002.png"), readBytes(none + "/decals_0002.png")) << "the shots left no mark";

    const std::string bad = outputPath("demo_shots_bad.txt");
    std::ofstream(bad) << "bullet 1 0.5 0.5\nbullet one 0.5 0.5\n";
    const Result refused = runDemo("decals --headless --shots " + bad);
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_NE(refused.output.find(bad + ":2:"), std::string::npos) << refused.output;
    const std::string outside = outputPath("demo_shots_outside.txt");
    std::ofstream(outside) << "click 1 5000 10\n";
    const Result off = runDemo("decals --headless --frames 2 --width 320 --height 180 --field 128 --out " + a +
                               " --shots " + outside);
    EXPECT_NE(off.exitCode, 0);
    EXPECT_NE(off.output.find("outside the 320x180 image"), std::string::npos) << off.output;
}

TEST(Demo, AnExplosionShowsOnceOnTheWall) {
    // The decal map spans the wall once: an explosion's crater and scorch change one patch of the
    // frame. (When the wall's texcoords ran 0..2 over the tiling map, each crater showed four
    // times, on patches a quarter of the frame apart.)
    const std::string shots = outputPath("demo_once_shots.txt"), none = outputPath("demo_once_none.txt");
    std::ofstream(shots) << "explosion 1 0.3 0.6 5\n";
    std::ofstream(none) << "# nothing\n";
    const std::string hit = outputPath("demo_once_hit"), clean = outputPath("demo_once_clean");
    const std::string args = "decals --headless --frames 3 --width 320 --height 180 --field 128 --out ";
    ASSERT_EQ(runDemo(args + hit + " --shots " + shots).exitCode, 0);
    ASSERT_EQ(runDemo(args + clean + " --shots " + none).exitCode, 0);
    const Image a = readImage(hit + "/decals_0002.png"), b = readImage(clean + "/decals_0002.png");
    int changed = 0, far = 0;
    double cx = 0.0, cy = 0.0;
    std::vector<std::pair<int, int>> where;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double d = 0.0;
            for (int c = 0; c < 3; ++c) d += std::abs(a.at(x, y, c) - b.at(x, y, c));
            if (d < 0.1) continue;
            ++changed;
            cx += x;
            cy += y;
            where.emplace_back(x, y);
        }
    ASSERT_GT(changed, 20) << "the explosion left no mark";
    cx /= changed;
    cy /= changed;
    for (const auto& [x, y] : where) far += std::hypot(x - cx, y - cy) > 30.0;
    std::printf("[once] %d pixels changed, %d of them more than 30 pixels from their centre (%.0f, %.0f)\n", changed, far,
                cx, cy);
    EXPECT_LE(far, changed / 50);
}

TEST(Demo, ThePillarTakesAClickWhereItsReliefIs) {
    // decals --pillar: the bricks on a column, a click picked on its relief (pickMesh) and
    // stamped there: around the clicked pixel the frame darkens (a hole, soot), and a run
    // without the click draws the same column.
    const std::string shots = outputPath("demo_pillar_shots.txt"), none = outputPath("demo_pillar_none.txt");
    std::ofstream(shots) << "click 1 170 95\n";
    std::ofstream(none) << "# nothing\n";
    const std::string shot = outputPath("demo_pillar_shot"), clean = outputPath("demo_pillar_clean"),
                      wall = outputPath("demo_pillar_wall");
    const std::string args = "decals --headless --frames 3 --width 320 --height 180 --field 128 --out ";
    for (const auto& [dir, list, pillar] : {std::tuple{shot, shots, " --pillar"}, std::tuple{clean, none, " --pillar"},
                                           std::tuple{wall, none, ""}}) {
        const Result r = runDemo(args + dir + " --shots " + list + pillar);
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    const Image a = readImage(shot + "/decals_0002.png"), b = readImage(clean + "/decals_0002.png");
    EXPECT_NE(readBytes(clean + "/decals_0002.png"), readBytes(wall + "/decals_0002.png")) << "no column was drawn";
    // The pixel that darkened most is the click's, within 2 pixels, and it darkened visibly.
    int darkest = 0;
    double most = 0.0;
    for (int i = 0; i < a.width * a.height; ++i) {
        double d = 0.0;
        for (int c = 0; c < 3; ++c) d += b.at(i % a.width, i / a.width, c) - a.at(i % a.width, i / a.width, c);
        if (d > most) most = d, darkest = i;
    }
    std::printf("[pillar] the click at (170, 95) darkened (%d, %d) most, by %.3f\n", darkest % a.width,
                darkest / a.width, most / 3.0);
    EXPECT_LE(std::hypot(darkest % a.width - 170.0, darkest / a.width - 95.0), 2.0);
    EXPECT_GT(most / 3.0, 0.1);
}

TEST(Demo, TheCameraTurnsAtItsRateForAVideo) {
    // --camera-turn 10: each frame's camera turned further round its target at 10 degrees a
    // second of the frames' time (the water's on the spot). Half-second frames: the third, a
    // second in, is the frame of a camera placed 10 degrees round (within the rounding of the
    // turns added up), and not the still camera's.
    for (const auto& [scene, placed] : {std::pair{"decals", " --camera-azimuth 75.8902"},
                                        std::pair{"water", " --camera-azimuth 10"}}) {
        const HalfSecondFrames turned = halfSecondFrames(scene, "turn_10", " --camera-turn 10");
        EXPECT_NE(turned.log.find("hfx: camera: turning 10.0 degrees a second"), std::string::npos) << turned.log;
        const Image& turning = turned.third;
        const Image still = halfSecondFrames(scene, "turn_still", "").third,
                    moved = halfSecondFrames(scene, "turn_placed", placed).third;
        const FrameDifference asPlaced = frameDifference(turning, moved), asStill = frameDifference(turning, still);
        std::printf("[turn] %s a second in: %.3f levels from the camera placed 10 degrees round, %.2f from the still "
                    "one\n",
                    scene, asPlaced.mean, asStill.mean);
        EXPECT_LT(asPlaced.mean, 0.5) << scene;
        EXPECT_GT(asStill.mean, 10.0 * std::max(asPlaced.mean, 0.1)) << scene;
    }
}

TEST(Demo, TheCameraPathPlacesEachFrameBetweenItsKeys) {
    // --camera-path: two keys a second apart, half-second frames. The second frame is halfway
    // in time, and the path eases in and out symmetrically (a cubic with no slope at either end),
    // so it is the frame of a camera placed halfway between the keys; the third is the last
    // key's. The water's camera also climbs (its height keys) as it turns.
    for (const auto& [scene, keys, halfway, last] :
         {std::tuple{"decals", "0 azimuth=65\n1 azimuth=85\n", " --camera-azimuth 75", " --camera-azimuth 85"},
          std::tuple{"water", "0 azimuth=0 height=7\n1 azimuth=20 height=27\n", " --camera-azimuth 10 --camera-height 17",
                     " --camera-azimuth 20 --camera-height 27"}}) {
        const std::string path = outputPath(std::string("demo_path_") + scene + ".txt");
        std::ofstream(path) << "# seconds, then the camera's placement\n" << keys;
        const HalfSecondFrames followed = halfSecondFrames(scene, "path", " --camera-path " + path);
        EXPECT_NE(followed.log.find("hfx: camera: following " + path + ", 2 keys over 1.00 s"), std::string::npos)
            << followed.log;
        const Image &pathMiddle = followed.second, &pathLast = followed.third;
        const Image placedMiddle = halfSecondFrames(scene, "path_halfway", halfway).second,
                    placedLast = halfSecondFrames(scene, "path_last", last).third;
        const FrameDifference middle = frameDifference(pathMiddle, placedMiddle), end = frameDifference(pathLast, placedLast),
                              apart = frameDifference(pathMiddle, pathLast);
        std::printf("[camera path] %s: halfway %.3f levels from the camera placed there, last %.3f; the two frames "
                    "%.2f apart\n",
                    scene, middle.mean, end.mean, apart.mean);
        EXPECT_LT(middle.mean, 0.5) << scene;
        EXPECT_LT(end.mean, 0.5) << scene;
        EXPECT_GT(apart.mean, 10.0 * std::max({middle.mean, end.mean, 0.1})) << scene;
    }
    // Between keys no value leaves the range of the two about it: a planet's camera that comes in
    // to 1.1 radii, holds there and goes out again never dips into the cloud tops (1.05), where a
    // Catmull-Rom spline through the same keys comes to 0.86 halfway through the hold.
    const std::string dive = outputPath("demo_path_dive.txt");
    std::ofstream(dive) << "0 distance=3\n1 distance=1.1\n2 distance=1.1\n3 distance=3\n";
    const Result dived = runDemo("planet --field 64 --spin-up 0 --headless --width 64 --height 36 --out " +
                                 outputPath("demo_path_dive") + " --camera-path " + dive);
    EXPECT_EQ(dived.exitCode, 0) << dived.output;
    // A path's faults are named with its file and line, or the time where the scene refuses it;
    // a value that only other scenes' cameras take is refused as its option is.
    const std::string bad = outputPath("demo_path_bad.txt");
    for (const auto& [args, keys, message] :
         {std::tuple{"water", "0 azimuth=0 elevation=10\n", "elevation (--camera-elevation) is for the decals, planet, "
                                                            "noise and maps scenes: the water scene does not take it"},
          std::tuple{"decals", "0 azimuth=0\n1 azimuth=10 distance=3\n", "line 2: names other values than line 1"},
          std::tuple{"decals", "0 elevation=95\n", "line 1: elevation 95 is outside -89 to 89 degrees"},
          std::tuple{"decals", "1 azimuth=0\n0.5 azimuth=3\n", "line 2: its time 0.5 s does not come after"},
          std::tuple{"decals", "0 target=1,2\n", "line 1: target takes three values, X,Y,Z, got '1,2'"},
          std::tuple{"decals", "0 target=1,,2,3\n", "line 1: target: '' is not a finite number"},
          std::tuple{"decals", "0 zoom=3\n", "line 1: 'zoom=3' is not NAME=VALUE"},
          std::tuple{"decals", "# nothing\n", "holds no key"},
          std::tuple{"decals --camera-turn 5", "0 azimuth=0\n", "--camera-path excludes --camera-turn"},
          std::tuple{"bench", "0 azimuth=0\n", "--camera-path is for the scenes' runs: bench draws each scene"},
          std::tuple{"planet --field 64 --spin-up 0", "0 distance=3 target=0,0,0\n2 distance=1.2 target=0,0,-0.5\n",
                     " at 1.5625 s: the planet's camera would stand 1.03 radii from its centre"}}) {
        std::ofstream(bad) << keys;
        const Result r = runDemo(std::string(args) + " --headless --camera-path " + bad);
        EXPECT_NE(r.exitCode, 0) << args << " " << keys;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << " " << keys << "\n" << r.output;
        if (std::string_view(args).find("--camera-turn") == std::string_view::npos && std::string_view(args) != "bench") {
            EXPECT_NE(r.output.find("camera path " + bad), std::string::npos) << r.output;
        }
    }
}

TEST(Demo, ThePillarIsClosedByCapstonesSeenFromAbove) {
    // Looked at from 60 degrees above, the column's top is a capstone: around the point where
    // its axis meets the top, a flat grey disc (channels within a few levels, little variation),
    // not the inside of an open tube (bricks, red over blue) nor the sky.
    const SeenPoint seen = renderAndFind(
        "pillar_above", "decals --pillar --field 128 --camera-target 0,1.6,0 --camera-elevation 60 --camera-distance 3",
        320, 180, Camera::orbit({0.0f, 1.6f, 0.0f}, 3.0f, 0.6f, glm::radians(60.0f)), {0.0f, 1.6f, 0.0f});
    const Image& frame = seen.frame;
    const int px = int(seen.pixel.x), py = int(seen.pixel.y); // (0.6: the scene's azimuth)
    ASSERT_TRUE(px >= 4 && px < 316 && py >= 4 && py < 176) << px << ", " << py;
    double sum[3] = {0, 0, 0}, sum2 = 0, mean = 0;
    int n = 0;
    for (int y = py - 4; y <= py + 4; ++y)
        for (int x = px - 4; x <= px + 4; ++x, ++n) {
            const double l = (frame.at(x, y, 0) + frame.at(x, y, 1) + frame.at(x, y, 2)) / 3.0;
            for (int c = 0; c < 3; ++c) sum[c] += frame.at(x, y, c);
            mean += l;
            sum2 += l * l;
        }
    mean /= n;
    const double spread = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
    const double red = sum[0] / n, green = sum[1] / n, blue = sum[2] / n;
    std::printf("[pillar] its top's centre at (%d, %d): (%.3f, %.3f, %.3f), spread %.4f\n", px, py, red, green, blue,
                spread);
    EXPECT_LT(std::abs(red - green), 0.06) << "not grey";
    EXPECT_LT(std::abs(green - blue), 0.06) << "not grey";
    EXPECT_LT(spread, 0.02) << "not flat";
    EXPECT_GT(std::abs(blue - frame.at(0, 0, 2)) + std::abs(red - frame.at(0, 0, 0)), 0.1) << "the sky";
}

TEST(Demo, TheTexelShadowsAreDrawnByDefaultWhereTheSurfaceHasFewerTexelsThanPixels) {
    // The noise plane covers most of a 320x180 image: a 64² field shows on about ten pixels per
    // texel (the texel shadows pay), a 256² one on well under one (they do not). The default
    // frame is the forced one's, to the byte, and the two forced frames differ (so the
    // comparison can tell them apart). The walks in the draw, where the policy can take them (a
    // compute pass's never do by default).
    for (const auto& [field, pays] : {std::pair{64, true}, std::pair{256, false}}) {
        const std::string args = "noise --headless --frames 2 --width 320 --height 180 --trace-pass draw --field " +
                                 std::to_string(field) + " --out ";
        std::string frames[3];
        const char* flags[3] = {"", " --texel-shadows", " --no-texel-shadows"};
        for (int k = 0; k < 3; ++k) {
            const std::string dir = outputPath("demo_auto_texels_" + std::to_string(field) + "_" + std::to_string(k));
            std::filesystem::remove_all(dir);
            const Result r = runDemo(args + dir + flags[k]);
            ASSERT_EQ(r.exitCode, 0) << r.output;
            frames[k] = readBytes(dir + "/noise_0001.png");
        }
        EXPECT_FALSE(frames[1] == frames[2]) << field << "²: the texel shadows change nothing here";
        EXPECT_TRUE(frames[0] == frames[pays ? 1 : 2])
            << field << "²: the default frame is not the one " << (pays ? "with" : "without") << " texel shadows";
    }
}

TEST(Demo, TheTexelShadowsDrawTheFlatScenesAsTheWalksDo) {
    // --texel-shadows reads hier's self-shadow from the texel shadows where the hard shadow does
    // not change between samples (the penumbra blended): the decal wall's and the noise plane's
    // frames stay within a small difference of the walked ones; the wall's far closer than its
    // frame without self-shadows is (the noise plane's shadows are faint at this size).
    for (const std::string scene : {"decals", "noise"}) {
        const Image walked = flatSceneFrame(scene, "texels_walked", " --no-texel-shadows"),
                    read = flatSceneFrame(scene, "texels_read", " --texel-shadows"),
                    unshadowed = flatSceneFrame(scene, "texels_unshadowed", " --no-shadows");
        const auto [mean, far] = frameDifference(walked, read);
        const auto [meanOff, farOff] = frameDifference(walked, unshadowed);
        std::printf("[texels] %s: %.3f levels apart on average, %.3f%% of pixels > 16 (without self-shadows: %.3f, "
                    "%.3f%%)\n", scene.c_str(), mean, 100.0 * far, meanOff, 100.0 * farOff);
        EXPECT_LE(mean, 0.25) << scene;
        EXPECT_LE(far, 0.002) << scene;
        if (scene == "decals") {
            EXPECT_GT(meanOff, 10.0 * std::max(mean, 0.05)) << scene << ": the comparison could not tell shadows apart";
        }
    }
}

TEST(Demo, APixelBudgetDrawsTheTexelShadowsAtAStrideWithinItWhereEverySampleWouldNotPay) {
    // The decal wall at 512² on a 320x180 image: about 0.1 pixels per texel, so the texel
    // shadows at every sample do not pay and are off by default. A budget of 3 pixels takes every
    // 8th sample on each axis (2.5 pixels apart on the screen, 6.4 pixels per sample): the frame
    // is drawn with them (it differs from the walked one) and stays close to the walked frame,
    // far closer than the frame without self-shadows is. The walks in the draw, where the policy
    // can take them.
    std::string log;
    const std::string flags = " --pixel-budget 3 --trace-pass draw";
    const Image read = flatSceneFrame("decals", "stride_read", flags, 512, &log),
                walked = flatSceneFrame("decals", "stride_walked", flags + " --no-texel-shadows", 512),
                unshadowed = flatSceneFrame("decals", "stride_unshadowed", flags + " --no-shadows", 512);
    EXPECT_NE(log.find("texel shadows on, stride 8"), std::string::npos) << log;
    const auto [mean, far] = frameDifference(walked, read);
    const double meanOff = frameDifference(walked, unshadowed).mean;
    std::printf("[stride] %.3f levels apart on average, %.3f%% of pixels > 16 (without self-shadows: %.3f)\n", mean,
                100.0 * far, meanOff);
    EXPECT_GT(mean, 0.0) << "the texel shadows were not read";
    EXPECT_LE(mean, 0.25);
    EXPECT_LE(far, 0.005);
    EXPECT_GT(meanOff, 10.0 * mean);
}

TEST(Demo, TheBeamStartDrawsTheFlatScenesAsTheWalkFromTheTopDoes) {
    // hier's beam start (on by default, --no-beam-start off) changes where the walks begin, not
    // what they hit: the decal wall's and the noise plane's frames with and without it are the
    // same image to the shading's rounding. Their frames without self-shadows differ (so the
    // comparison can tell frames apart).
    for (const std::string scene : {"decals", "noise"}) {
        const Image started = flatSceneFrame(scene, "beam_started", ""),
                    walked = flatSceneFrame(scene, "beam_walked", " --no-beam-start"),
                    unshadowed = flatSceneFrame(scene, "beam_unshadowed", " --no-beam-start --no-shadows");
        ASSERT_EQ(started.pixels.size(), walked.pixels.size());
        double most = 0.0, mostOff = 0.0;
        for (size_t i = 0; i < started.pixels.size(); ++i) {
            most = std::max(most, 255.0 * std::abs(double(started.pixels[i]) - walked.pixels[i]));
            mostOff = std::max(mostOff, 255.0 * std::abs(double(unshadowed.pixels[i]) - walked.pixels[i]));
        }
        std::printf("[beam] %s: at most %.1f levels apart (without self-shadows: %.1f)\n", scene.c_str(), most, mostOff);
        EXPECT_LE(most, 2.0) << scene;
        EXPECT_GT(mostOff, 16.0) << scene << ": the comparison could not tell frames apart";
    }
}

TEST(Demo, TheTracePassDrawsTheScenesAsTheDrawDoes) {
    // --trace-pass compute (hier's walks in a compute pass) against draw (the walks in the surface
    // draw, llvmpipe's choice): the decal wall (its shadow map's caster too) and the
    // planet (a sphere, a silhouette fade) draw the same frame but where a 2x2 quad has a helper
    // lane, whose hit the shading draw takes from a neighbour's (docs/BENCHMARKS.md);
    // the log says where the walks ran. Normal mapped, the frames differ ten times as much at
    // least (measured: decals 0.024 levels on average against 14.1, the planet 0.018 against 0.83).
    for (const std::string scene : {"decals", "planet"}) {
        std::string computedLog, walkedLog;
        const Image computed = flatSceneFrame(scene, "pass_computed", " --trace-pass compute", 128, &computedLog),
                    walked = flatSceneFrame(scene, "pass_walked", " --trace-pass draw", 128, &walkedLog),
                    flat = flatSceneFrame(scene, "pass_flat", " --technique nm");
        EXPECT_NE(computedLog.find("hier walked in a compute pass"), std::string::npos) << computedLog;
        EXPECT_NE(walkedLog.find("hier walked in the draw"), std::string::npos) << walkedLog;
        const FrameDifference d = frameDifference(computed, walked), off = frameDifference(flat, walked);
        std::printf("[trace pass] %s: mean %.3f levels apart, %.3f%% of pixels by more than 16 (normal mapped: "
                    "%.3f, %.3f%%)\n",
                    scene.c_str(), d.mean, 100.0 * d.far, off.mean, 100.0 * off.far);
        EXPECT_LE(d.mean, 0.1) << scene;
        EXPECT_LE(d.far, 0.001) << scene;
        EXPECT_GT(off.mean, 10.0 * d.mean) << scene << ": the comparison could not tell frames apart";
    }
}

TEST(Demo, AReversedZRunDrawsTheScenesFrames) {
    // --reversed-z: every user's scene drawn as an engine with a reversed depth buffer draws it
    // (GL_ZERO_TO_ONE, GL_GREATER, cleared to 0), the water's sky and its POM, the wall's hier
    // and its shadow map, the planet's sphere and its rings: the frames of GL's default depth
    // (measured: at most 1 level apart, on the water). A frame one field step later differs by
    // far more, so the comparison can tell frames apart; the log says the camera was reversed (a
    // reversed camera drawn without GL_ZERO_TO_ONE set would be refused).
    for (const std::string scene : {"water", "decals", "planet"}) {
        // (The planet's weather moves little in a 30th of a second: its frames a tenth apart.)
        const std::string flags = scene == "planet" ? " --rings 1 --dt 0.1" : "";
        std::string standardLog, reversedLog;
        const Image standard = flatSceneFrame(scene, "depth_standard", flags, 128, &standardLog),
                    reversed = flatSceneFrame(scene, "depth_reversed", flags + " --reversed-z", 128, &reversedLog);
        EXPECT_NE(reversedLog.find("hfx: depth: reversed Z"), std::string::npos) << reversedLog;
        EXPECT_EQ(standardLog.find("hfx: depth: reversed Z"), std::string::npos) << standardLog;
        const FrameDifference d = frameDifference(standard, reversed);
        EXPECT_LE(d.mean, 0.05) << scene;
        EXPECT_EQ(d.far, 0.0) << scene;
        const std::string dir = outputPath("demo_depth_standard_" + scene);
        const FrameDifference step = frameDifference(readImage(dir + "/" + scene + "_0000.png"), standard);
        EXPECT_GT(step.mean, 20.0 * std::max(d.mean, 0.01)) << scene;
    }
}

TEST(Demo, TheWatersSkyCloudsOverAndItsHazeThickensWithTheWind) {
    // The water's weather follows its wind: fair cumulus over 0.4 of the sky at Beaufort 4,
    // overcast (0.95, a veil over its gaps) and a spray haze at a storm (10), and --clouds holds
    // the clouds. The storm's sky (the frame's top fifth) is greyer: less blue over red than the
    // breeze's.
    std::string breeze, storm, held;
    const Image calm = flatSceneFrame("water", "weather_4", " --beaufort 4", 64, &breeze);
    const Image rough = flatSceneFrame("water", "weather_10", " --beaufort 10", 64, &storm);
    flatSceneFrame("water", "weather_held", " --beaufort 10 --clouds 0.3", 64, &held);
    EXPECT_NE(breeze.find("hfx: weather: clouds over 0.40 of the sky (the wind's: --clouds sets them), haze half the "
                          "colour at 2500 m"),
              std::string::npos)
        << breeze;
    EXPECT_NE(storm.find("hfx: weather: clouds over 0.95 of the sky (the wind's: --clouds sets them), a veil over 0.93 "
                         "of their gaps, haze half the colour at 1200 m"),
              std::string::npos)
        << storm;
    EXPECT_NE(held.find("hfx: weather: clouds over 0.30 of the sky (--clouds), haze half the colour at 1200 m"),
              std::string::npos)
        << held;
    auto blueOverRed = [](const Image& image) {
        double sum = 0.0;
        for (int y = 0; y < image.height / 5; ++y)
            for (int x = 0; x < image.width; ++x) sum += image.at(x, y, 2) - image.at(x, y, 0);
        return sum / (image.width * (image.height / 5));
    };
    std::printf("[weather] the sky's blue over red: %.3f at Beaufort 4, %.3f at 10\n", blueOverRed(calm),
                blueOverRed(rough));
    EXPECT_GT(blueOverRed(calm), blueOverRed(rough) + 0.05) << "the storm's sky is as blue as the breeze's";
}

TEST(Demo, TheWatersFirstFrameIsASeaThatHasBlownAWhile) {
    // The water's first frame was a clear start: a storm without whitecaps, its streaks crossing
    // bare water as scratches, where the gallery's frames (--foam-history 20) showed the foam
    // that five of its half-lives leave. The default now is those 20 s: the log says so, the
    // frame is --foam-history 20's, and a clear start (0) is another sea (fewer whitecaps, no
    // streaks yet: OceanShading.AGalesStreaksBuildAsItsFoamDoes).
    std::string log;
    const Image settled = flatSceneFrame("water", "foam_default", " --beaufort 10", 128, &log);
    const Image twenty = flatSceneFrame("water", "foam_20", " --beaufort 10 --foam-history 20", 128);
    const Image clear = flatSceneFrame("water", "foam_0", " --beaufort 10 --foam-history 0", 128);
    EXPECT_NE(log.find("; the first frame's foam had 20 s of this wind behind it (--foam-history)"), std::string::npos)
        << log;
    const FrameDifference same = frameDifference(settled, twenty), other = frameDifference(settled, clear);
    std::printf("[foam history] the default against 20 s: %.3f levels apart on average; against a clear start %.2f, "
                "%.1f%% of pixels more than 16 apart\n",
                same.mean, other.mean, 100.0 * other.far);
    EXPECT_LT(same.mean, 0.5) << "the default is not --foam-history 20";
    EXPECT_GT(other.far, 0.05) << "20 s of foam look like a clear start";
}

TEST(Demo, TheWatersCloudsStartWithTheSunOutWhereTheDefaultViewLooks) {
    // The clouds' layer starts where it leaves the sea the default view looks at in full sun
    // (the sunniest start under an overcast deck): the middle of its first frames, the waves the
    // camera looks at, is lit as under a clear sky, not darkened by a cloud's shadow by chance
    // (as the gallery's frames were until 2026-11-30). The frame's middle (a third of its width,
    // from just under the horizon to three quarters down) with the default clouds over it under
    // a clear sky: their mean luminance, and how far apart they are.
    auto middle = [](const Image& image) {
        double sum = 0.0;
        int n = 0;
        for (int y = image.height * 45 / 100; y < image.height * 3 / 4; ++y)
            for (int x = image.width / 3; x < image.width * 2 / 3; ++x, ++n)
                sum += 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
        return sum / n;
    };
    const double clouded = middle(flatSceneFrame("water", "sunny_start", "", 256)),
                 clear = middle(flatSceneFrame("water", "sunny_clear", " --clouds 0", 256));
    std::printf("[sunny start] the view's middle: %.3f under the clouds, %.3f under a clear sky\n", clouded, clear);
    EXPECT_GT(clouded, 0.9 * clear) << "the sea the default view looks at lies in a cloud's shadow";
}

TEST(Demo, AnOrthographicRunDrawsEachScenesParallelView) {
    // --orthographic: every user's scene drawn with parallel rays (glm::ortho framing the lens's
    // view at its target). The decal wall, a rectangle seen at an angle, is then as wide on every
    // row of the frame (its edges parallel), where the lens's perspective narrows it towards its
    // far edge; the sea and the planet draw other frames than the lens's; the log says so.
    for (const std::string scene : {"decals", "planet", "water"}) {
        std::string log;
        const Image lens = flatSceneFrame(scene, "projection_lens", ""),
                    parallel = flatSceneFrame(scene, "projection_ortho", " --orthographic", 128, &log);
        EXPECT_NE(log.find("hfx: projection: orthographic"), std::string::npos) << log;
        EXPECT_GT(frameDifference(lens, parallel).mean, 5.0) << scene << ": the projection made no difference";
        if (scene != "decals") continue;
        // The wall's width on each row: its pixels apart from the sky's (the top-left corner's).
        auto widths = [](const Image& frame) {
            std::vector<int> out;
            for (int y = 0; y < frame.height; ++y) {
                int wall = 0;
                for (int x = 0; x < frame.width; ++x) {
                    float d = 0.0f;
                    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(frame.at(x, y, c) - frame.at(0, 0, c)));
                    wall += d > 8.0f / 255.0f;
                }
                out.push_back(wall);
            }
            return out;
        };
        const std::vector<int> a = widths(parallel), b = widths(lens);
        const auto [aMin, aMax] = std::minmax_element(a.begin(), a.end());
        const auto [bMin, bMax] = std::minmax_element(b.begin(), b.end());
        std::printf("[orthographic] the wall is %d to %d pixels wide by row; through the lens %d to %d\n", *aMin, *aMax,
                    *bMin, *bMax);
        EXPECT_GT(*aMin, parallel.width / 5) << "no wall";
        EXPECT_LE(*aMax - *aMin, 1) << "the wall's edges are not parallel";
        EXPECT_GT(*bMax - *bMin, 10) << "the lens's view would pass as well";
    }
}

TEST(Demo, TheCameraOptionsPlaceEachScenesCamera) {
    // --camera-azimuth, --camera-elevation and --camera-distance move the camera about its
    // target (--camera-target) from where the scene put it; the log says where it stands. The decal wall (4 units
    // square, centred on the target) seen head-on from 8 and 16 units is a square in the middle
    // of the frame, its edges parallel to the frame's, half as wide from twice as far; the
    // scene's own camera grazes it (a trapezoid).
    std::string log;
    const Image grazing = flatSceneFrame("decals", "camera_own", "", 128, &log);
    EXPECT_NE(log.find("hfx: camera: azimuth 65.9, elevation 8.6 degrees, distance 3.40"), std::string::npos) << log;
    struct Extent { // the wall's pixels apart from the sky's (the top-left corner's)
        int left = 1 << 20, right = -1, top = 1 << 20, bottom = -1, minRow = 1 << 20, maxRow = 0;
    };
    auto extent = [](const Image& frame) {
        Extent e;
        for (int y = 0; y < frame.height; ++y) {
            int row = 0;
            for (int x = 0; x < frame.width; ++x) {
                float d = 0.0f;
                for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(frame.at(x, y, c) - frame.at(0, 0, c)));
                if (d <= 8.0f / 255.0f) continue;
                ++row;
                e.left = std::min(e.left, x), e.right = std::max(e.right, x);
                e.top = std::min(e.top, y), e.bottom = std::max(e.bottom, y);
            }
            if (row > 0) e.minRow = std::min(e.minRow, row), e.maxRow = std::max(e.maxRow, row);
        }
        return e;
    };
    Extent headOn[2];
    for (int i = 0; i < 2; ++i) {
        const int distance = 8 << i;
        const Image frame = flatSceneFrame("decals", "camera_" + std::to_string(distance),
                                           " --camera-azimuth 0 --camera-elevation 0 --camera-distance " +
                                               std::to_string(distance),
                                           128, &log);
        EXPECT_NE(log.find("hfx: camera: azimuth 0.0, elevation 0.0 degrees, distance " + std::to_string(distance) + ".00"),
                  std::string::npos)
            << log;
        const Extent& e = headOn[i] = extent(frame);
        const int width = e.right - e.left + 1, height = e.bottom - e.top + 1;
        std::printf("[camera] head-on from %d: the wall %dx%d pixels at (%d, %d), rows %d to %d wide\n", distance, width,
                    height, e.left, e.top, e.minRow, e.maxRow);
        EXPECT_NEAR(width, height, 2) << "not square";
        EXPECT_NEAR(e.left, frame.width - 1 - e.right, 2) << "not in the middle";
        EXPECT_NEAR(e.top, frame.height - 1 - e.bottom, 2) << "not in the middle";
        EXPECT_LE(e.maxRow - e.minRow, 1) << "its edges lean";
    }
    const double ratio = double(headOn[0].right - headOn[0].left + 1) / double(headOn[1].right - headOn[1].left + 1);
    EXPECT_NEAR(ratio, 2.0, 0.1) << "twice as far is not half as wide";
    // Looking at a point 1 unit right of the wall's centre from 8 units, the wall's centre sits a
    // quarter of its width (4 units wide) left of the frame's.
    const Image shifted = flatSceneFrame("decals", "camera_target",
                                         " --camera-azimuth 0 --camera-elevation 0 --camera-distance 8 "
                                         "--camera-target 1,0,0",
                                         128, &log);
    EXPECT_NE(log.find("distance 8.00 from its target (1.00, 0.00, 0.00)"), std::string::npos) << log;
    const Extent moved = extent(shifted);
    const double centre = 0.5 * (moved.left + moved.right), frameCentre = 0.5 * (shifted.width - 1),
                 quarter = 0.25 * (headOn[0].right - headOn[0].left + 1);
    std::printf("[camera] looking 1 unit right of it: the wall's centre %.1f pixels left of the frame's (a quarter "
                "of its width: %.1f)\n",
                frameCentre - centre, quarter);
    EXPECT_NEAR(frameCentre - centre, quarter, 1.5);
    EXPECT_NEAR(moved.right - moved.left, headOn[0].right - headOn[0].left, 1) << "the distance changed";
    const Extent own = extent(grazing);
    EXPECT_GT(own.maxRow - own.minRow, 10) << "the scene's own camera would pass as head-on";
    // The water's camera keeps its place and pitch and turns away from the low sun.
    const Image sunward = flatSceneFrame("water", "camera_sunward", "", 128, &log);
    EXPECT_NE(log.find("hfx: camera: azimuth 0.0 degrees (looking along -z at 0), 8.0 below the horizon, 7 m"),
              std::string::npos)
        << log;
    const Image away = flatSceneFrame("water", "camera_away", " --camera-azimuth 180", 128, &log);
    EXPECT_NE(log.find("hfx: camera: azimuth 180.0 degrees"), std::string::npos) << log;
    EXPECT_GT(frameDifference(sunward, away).mean, 5.0) << "the turn made no difference";
    const Image high = flatSceneFrame("water", "camera_high", " --camera-height 100", 128, &log);
    EXPECT_NE(log.find("8.0 below the horizon, 100 m above the sea"), std::string::npos) << log;
    EXPECT_GT(frameDifference(sunward, high).mean, 5.0) << "the height made no difference";
}

TEST(Demo, AutoSaysWhichTracePassItTimedFasterWhereNoWorkaroundDecides) {
    // --trace-pass auto where no workaround decides (trace-in-draw off: a GPU's case): the trial
    // times both passes on the first 8 frames and the log gives its choice and both medians; with
    // llvmpipe's own workarounds the log names the draw and no trial.
    std::string tried, decided;
    {
        const WorkaroundsSet set("trace-in-draw=0");
        const std::string dir = outputPath("demo_pass_trial");
        std::filesystem::remove_all(dir);
        const Result r = runDemo("decals --headless --frames 10 --width 160 --height 90 --field 128 --out " + dir);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        tried = r.output;
    }
    const std::string dir = outputPath("demo_pass_device");
    std::filesystem::remove_all(dir);
    const Result r = runDemo("decals --headless --frames 10 --width 160 --height 90 --field 128 --out " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    decided = r.output;
    const size_t at = tried.find("hfx: hier walked in ");
    ASSERT_NE(at, std::string::npos) << tried;
    const std::string line = tried.substr(at, tried.find('\n', at) - at);
    std::printf("[trace pass trial] %s\n", line.c_str());
    EXPECT_TRUE(line.find("the draw (auto: ") != std::string::npos || line.find("a compute pass (auto: ") != std::string::npos)
        << line;
    EXPECT_NE(line.find(" ms)"), std::string::npos) << line;
    EXPECT_NE(decided.find("hfx: hier walked in the draw\n"), std::string::npos) << decided;
}

// Save and load: a run that loads the damage log another run saved draws, on its first frame,
// exactly the last frame of the run that saved it (a late-joining client sees the same wall).
TEST(Demo, ASavedDamageLogLoadsIntoTheSameWall) {
    const std::string a = outputPath("demo_damage_a"), b = outputPath("demo_damage_b"), c = outputPath("demo_damage_c");
    const std::string log = outputPath("demo_damage.log");
    const std::string args = " --headless --width 320 --height 180 --field 128 --out ";
    const Result saved = runDemo("decals --frames 8" + args + a + " --save-damage " + log);
    ASSERT_EQ(saved.exitCode, 0) << saved.output;
    EXPECT_NE(saved.output.find("saved"), std::string::npos) << saved.output;
    const Result loaded = runDemo("decals --frames 1" + args + b + " --load-damage " + log);
    ASSERT_EQ(loaded.exitCode, 0) << loaded.output;
    EXPECT_EQ(readBytes(a + "/decals_0007.png"), readBytes(b + "/decals_0000.png"));
    const Result fresh = runDemo("decals --frames 1" + args + c);
    ASSERT_EQ(fresh.exitCode, 0) << fresh.output;
    EXPECT_NE(readBytes(c + "/decals_0000.png"), readBytes(b + "/decals_0000.png")) << "the log drew nothing";

    const std::string bad = outputPath("demo_damage_bad.log");
    std::ofstream(bad) << "hfx-damage 1\nnow 0\nimpact rocket 0.5 0.5 0 0 1 0.1 1 0 1\n";
    const Result refused = runDemo("decals --frames 1" + args + b + " --load-damage " + bad);
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_NE(refused.output.find(bad + ":3: unknown impact kind 'rocket'"), std::string::npos) << refused.output;
}

// Every scene takes impacts: a shot list's explosion (pixels) rings the water and stirs a storm
// on the planet; a shot outside the image is refused by line.
TEST(Demo, ImpactsLandInTheWaterAndOnThePlanet) {
    const std::string shots = outputPath("demo_impact_shots.txt");
    std::ofstream(shots) << "explosion 1 80 60 3\nclick 1 100 70\n";
    for (const char* scene : {"water", "planet"}) {
        const std::string hit = outputPath(std::string("demo_impact_") + scene), calm = hit + "_none";
        const std::string args = std::string(scene) + " --headless --frames 3 --width 160 --height 90 --field 64 --out ";
        const Result r = runDemo(args + hit + " --shots " + shots);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find(std::string("impact: explosion at")), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(std::string("on the ") + (std::string(scene) == "water" ? "ocean" : "planet")),
                  std::string::npos) << r.output;
        const Result none = runDemo(args + calm);
        ASSERT_EQ(none.exitCode, 0) << none.output;
        EXPECT_NE(readBytes(hit + "/" + scene + "_0002.png"), readBytes(calm + "/" + scene + "_0002.png")) << scene;
    }
    const std::string outside = outputPath("demo_impact_outside.txt");
    std::ofstream(outside) << "explosion 1 900 10 1\n";
    const Result off = runDemo("water --headless --frames 2 --width 160 --height 90 --field 64 --out " +
                               outputPath("demo_impact_off") + " --shots " + outside);
    EXPECT_NE(off.exitCode, 0);
    EXPECT_NE(off.output.find("line 1"), std::string::npos) << off.output;
}

TEST(Demo, ThePlanetsPoleDrawsNoDarkDot) {
    // Seen from 80 degrees up, close: round the pole the traced hits of neighbouring pixels lie
    // far apart in u, and the shading read from their spread took texels that average the bands
    // round it, a dark dot 0.8 as bright as what surrounds it. The darkest pixel within 2 of the
    // pole against the mean of those 6 to 10 pixels from it.
    const SeenPoint seen = renderAndFind(
        "planet_pole", "planet --field 128 --spin-up 5 --camera-elevation 80 --camera-distance 1.6", 640, 360,
        Camera::orbit({0.0f, 0.0f, 0.0f}, 1.6f, 0.3f, glm::radians(80.0f)), {0.0f, 1.0f, 0.0f}); // the north pole
    const Image& frame = seen.frame;
    const double px = seen.pixel.x - 0.5, py = seen.pixel.y - 0.5; // (0.3: the scene's azimuth)
    ASSERT_TRUE(px > 12 && px < 628 && py > 12 && py < 348) << px << ", " << py;
    double darkest = 1e9, around = 0.0;
    int n = 0;
    for (int y = int(py) - 11; y <= int(py) + 11; ++y)
        for (int x = int(px) - 11; x <= int(px) + 11; ++x) {
            const double l = frame.at(x, y, 0) + frame.at(x, y, 1) + frame.at(x, y, 2), d = std::hypot(x - px, y - py);
            if (d <= 2.0) darkest = std::min(darkest, l);
            if (d >= 6.0 && d <= 10.0) around += l, ++n;
        }
    around /= n;
    std::printf("[pole] the darkest pixel at the pole %.3f of its surroundings' brightness\n", darkest / around);
    EXPECT_GT(darkest / around, 0.92);
}

// --rings 1 gives the planet its rings: from 5 radii they reach out beside the disc, where the
// ringless frame is black sky.
TEST(Demo, ThePlanetsRingsShowBesideItsDisc) {
    double beside[2];
    for (int rings = 0; rings < 2; ++rings) {
        const std::string out = outputPath(std::string("demo_rings_") + std::to_string(rings));
        const Result r = runDemo("planet --headless --frames 1 --width 320 --height 180 --field 64 --camera-distance 5 "
                                 "--rings " + std::to_string(rings) + " --out " + out);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const Image frame = readImage(out + "/planet_0000.png");
        // Left of the disc (x 117-202 of 320 at this distance), the rings' band (x 52-267).
        double sum = 0.0;
        int n = 0;
        for (int y = 80; y < 120; ++y)
            for (int x = 58; x < 108; ++x, ++n) sum += (frame.at(x, y, 0) + frame.at(x, y, 1) + frame.at(x, y, 2)) / 3.0;
        beside[rings] = sum / n;
    }
    std::printf("[rings] mean display value left of the disc: %.3f without, %.3f with rings\n", beside[0], beside[1]);
    EXPECT_LT(beside[0], 0.03);
    EXPECT_GT(beside[1], 0.1);
}

TEST(Demo, WritesAVideoWhenFfmpegIsThere) {
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "ffmpeg is not installed (Debian package ffmpeg)";
    const std::string video = outputPath("demo_video/water.mp4");
    std::filesystem::remove_all(outputPath("demo_video"));
    const Result r = runDemo("water --headless --frames 4 --width 160 --height 90 --field 64 --video " + video);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(std::filesystem::exists(video)) << r.output;
    EXPECT_GT(std::filesystem::file_size(video), 1000u);
}

TEST(Demo, OpensAWindowUnderXvfb) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
    const std::string out = outputPath("demo_window");
    std::filesystem::remove_all(out);
    // (The camera turning, as --camera-turn turns the window's orbit.)
    const Result r = runDemo("water --frames 3 --width 320 --height 180 --field 64 --camera-turn 30 --out " + out,
                             "xvfb-run -a -s '-screen 0 640x480x24'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("hfx: GL GLFW window: OpenGL 4.5"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("hfx: camera: turning 30.0 degrees a second"), std::string::npos) << r.output;
    EXPECT_GT(luminanceStdDev(readImage(out + "/water_0002.png")), 0.02);
    // The decal scene with its panel, closed by the frame count. The window's last frame holds
    // the rendered image scaled to the window plus the panel: its top-left corner (where the
    // panel opens) differs from the rendered frame's.
    const std::string shot = out + "/window.png";
    const Result decals = runDemo("decals --frames 3 --width 320 --height 180 --field 128 --out " + out +
                                      " --window-shot " + shot,
                                  "xvfb-run -a -s '-screen 0 640x480x24'");
    ASSERT_EQ(decals.exitCode, 0) << decals.output;
    const Image frame = readImage(out + "/decals_0002.png");
    EXPECT_GT(luminanceStdDev(frame), 0.02);
    const Image window = readImage(shot);
    ASSERT_EQ(window.width, 320) << "the window opens at --width x --height";
    double panel = 0.0;
    for (int y = 10; y < 40; ++y)
        for (int x = 10; x < 100; ++x)
            for (int c = 0; c < 3; ++c) panel += std::abs(window.at(x, y, c) - frame.at(x, y, c));
    EXPECT_GT(panel / (30 * 90 * 3), 0.05) << "no panel drawn over the frame";
}

TEST(Demo, NoOpenClPlatformSaysWhatToInstall) {
    // The ICD loader reads its drivers from OCL_ICD_VENDORS: an empty folder means no platform.
    const std::string empty = outputPath("demo_no_icd");
    std::filesystem::create_directories(empty);
    const Result r = runDemo("water --headless --frames 1 --out " + outputPath("demo_no_icd_frames"),
                             "env -u DISPLAY -u WAYLAND_DISPLAY OCL_ICD_VENDORS='" + empty + "'");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("no OpenCL platform"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("apt-get install pocl-opencl-icd"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos) << r.output;
}

TEST(Demo, TheExternalMemoryPathWithoutAVulkanDriverSaysWhatIsMissing) {
    // The Vulkan loader reads its drivers' manifests from VK_ICD_FILENAMES (VK_DRIVER_FILES since
    // 1.3.234): one that does not exist means no driver. The path is asked for by name, so it is
    // refused, naming what is missing, before a frame is drawn.
    const Result r = runDemo("noise --headless --frames 1 --width 64 --height 64 --field 64 --transfer external-memory "
                             "--out " + outputPath("demo_no_vulkan"),
                             "env -u DISPLAY -u WAYLAND_DISPLAY VK_ICD_FILENAMES=/nonexistent/hfx_icd.json "
                             "VK_DRIVER_FILES=/nonexistent/hfx_icd.json");
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("the external-memory transfer path is not available here: "), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("Vulkan"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(outputPath("demo_no_vulkan") + "/noise_0000.png")) << r.output;
}

TEST(Demo, TheGlContextAndTheClDeviceAreChosenByOptionAndNamed) {
    // Both EGL and OSMesa give llvmpipe here: the same frame, and each run says which it got.
    std::string osmesaLog, eglLog;
    const Image osmesa = flatSceneFrame("decals", "gl_osmesa", " --gl osmesa", 128, &osmesaLog);
    const Image egl = flatSceneFrame("decals", "gl_egl", " --gl egl", 128, &eglLog);
    EXPECT_NE(osmesaLog.find("hfx: GL OSMesa: OpenGL 4.5"), std::string::npos) << osmesaLog;
    EXPECT_NE(eglLog.find("hfx: GL EGL"), std::string::npos) << eglLog;
    EXPECT_EQ(frameDifference(osmesa, egl).far, 0.0);
    EXPECT_LT(frameDifference(osmesa, egl).mean, 0.5);
    // The OpenCL device by a part of its label, named with the reason it was taken.
    const Result cpu = runDemo("noise --headless --frames 1 --width 64 --height 64 --cl-device cpu --out " +
                               outputPath("demo_cl_cpu"));
    ASSERT_EQ(cpu.exitCode, 0) << cpu.output;
    EXPECT_NE(cpu.output.find("hfx: OpenCL device"), std::string::npos) << cpu.output;
    EXPECT_NE(cpu.output.find("filters: platform '', device 'cpu'"), std::string::npos) << cpu.output;
    const Result none = runDemo("noise --headless --frames 1 --cl-device no-such-device-xyz");
    EXPECT_NE(none.exitCode, 0);
    EXPECT_NE(none.output.find("no-such-device-xyz"), std::string::npos) << none.output;
    EXPECT_NE(none.output.find("devices present"), std::string::npos) << none.output;
    const Result glide = runDemo("noise --headless --gl glide");
    EXPECT_NE(glide.exitCode, 0);
    EXPECT_NE(glide.output.find("glide"), std::string::npos) << glide.output;
    const Result badEnv = runDemo("noise --headless --frames 1", "env -u DISPLAY -u WAYLAND_DISPLAY HFX_GL=glide");
    EXPECT_NE(badEnv.exitCode, 0);
    EXPECT_NE(badEnv.output.find("HFX_GL"), std::string::npos) << badEnv.output;
}

TEST(Demo, UnknownSceneIsAClearError) {
    const Result r = runDemo("volcano --headless");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("unknown scene 'volcano'"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos);
}

TEST(Demo, AnOutputFolderThatCannotBeMadeIsNamedBeforeAnyDeviceOpens) {
    // A file where the folder's parent should be: each option that names a folder is refused by
    // name, with the folder, before the devices open (no device line in the log).
    const std::string file = outputPath("demo_not_a_folder");
    std::ofstream(file) << "a file\n";
    for (const std::string option : {"--out", "--export-maps", "--video"}) {
        const std::string folder = file + "/frames";
        const std::string target = option == "--video" ? folder + "/water.mp4" : folder;
        const Result r = runDemo("water --headless --frames 1 --width 64 --height 64 " + option + " " + target);
        EXPECT_NE(r.exitCode, 0) << option;
        EXPECT_NE(r.output.find(option + ": cannot make the folder '" + folder + "'"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("hfx: OpenCL device"), std::string::npos) << option << ": named after the devices opened\n"
                                                                        << r.output;
    }
    // The benches too, before their minutes.
    const Result bench = runDemo("bench-tracers --out " + file + "/tracers");
    EXPECT_NE(bench.exitCode, 0);
    EXPECT_NE(bench.output.find("--out: cannot make the folder"), std::string::npos) << bench.output;
}

TEST(Demo, TheReadmesTechniqueTableIsTheOneTheTablePrints) {
    // The C++ table drives the docs: README.md carries `hfx-demo techniques` verbatim.
    const Result r = runDemo("techniques");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output, techniqueTableMarkdown());
    std::ifstream readme(HFX_SOURCE_DIR "/README.md");
    const std::string text((std::istreambuf_iterator<char>(readme)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find(r.output), std::string::npos) << "README.md's technique table differs from:\n" << r.output;
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
    // A map from files goes down the generated fields' pipeline: the hierarchical tracer (it
    // needs the per-frame pyramid), the smaller formats and both transfer paths.
    for (const char* args : {"--technique hier", "--technique hier --surface-format float16 --transfer map",
                             "--surface-format unorm8 --transfer pixel-buffer"}) {
        const std::string variant = outputPath("demo_maps_variant");
        const Result r = runDemo("maps --headless --width 160 --height 90 --height-map " + heightMap + " " + args +
                                 " --out " + variant);
        ASSERT_EQ(r.exitCode, 0) << args << "\n" << r.output;
        EXPECT_GT(luminanceStdDev(readImage(variant + "/maps_0000.png")), 0.02) << args;
    }

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
                             "water --samples-min 40 --samples-max 10", "water --width abc", "water --waves tidal",
                             "water --wind-speed -4", "water --depth-scale 2", "water --lod-threshold -1",
                             "water --dt 0", "water --field 100", "decals --shots /no/such/shots.txt",
                             "decals --normal-map n.png",  /* a normal map without a height map */ "water --environment /no/such/sky.exr",
                             "planet --field 4", "water --height 9", "planet --camera-distance 1", "decals --camera-elevation 90", "noise --texel-shadows --no-texel-shadows",
                             "decals --trace-pass sideways", "water --clouds 1.5"}) {
        const Result r = runDemo(std::string(args) + " --headless");
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_FALSE(r.output.empty()) << args << " printed nothing";
    }
    const Result r = runDemo("water --technique raytrace --headless");
    EXPECT_NE(r.output.find("raytrace"), std::string::npos) << r.output;
    // hier traces one grid: the ocean's cascades asked of it are refused by name, not dropped.
    const Result cascades = runDemo("water --technique hier --cascades 3 --headless --field 64");
    EXPECT_NE(cascades.exitCode, 0);
    EXPECT_NE(cascades.output.find("--cascades 3"), std::string::npos) << cascades.output;
    // An option that only other scenes take is refused by name, not ignored; one the scene takes
    // (the water's shot list: the water, the wall and the planet take impacts) passes that check.
    // So is one only hier reads where the headless run draws another technique, and one that a
    // switch beside it undoes, and one for a window where none opens; --trace-pass auto, the default
    // restated, passes.
    for (const auto& [args, message] :
         {std::pair{"water --rings 1", "--rings is for the planet scene: the water scene"},
          std::pair{"planet --height-map wall.png", "--height-map is for the maps and decals scenes: the planet"},
          std::pair{"noise --shots shots.txt", "--shots is for the decals, water and planet scenes: the noise"},
          std::pair{"decals --beaufort 3", "--beaufort is for the water scene"},
          std::pair{"water --trace-pass compute", "--trace-pass is for the hier technique, and the water scene draws pom"},
          std::pair{"decals --field 64 --technique nm --no-beam-start", "--no-beam-start is for the hier technique"},
          std::pair{"planet --texel-shadows", "--texel-shadows is for the decals, noise and maps scenes"},
          std::pair{"noise --no-shadows --texel-shadows", "--no-shadows excludes --texel-shadows"},
          std::pair{"decals --no-texel-shadows --defer-shadow-walks", "excludes --defer-shadow-walks"},
          std::pair{"water --window-shot shot.png", "--window-shot saves what a window shows, and this run is headless"},
          std::pair{"water --triplanar 1", "--triplanar is for the noise scene: the water scene"},
          std::pair{"decals --clouds 0.5", "--clouds is for the water scene: the decals scene"},
          std::pair{"noise --triplanar 1 --texel-shadows",
                    "--texel-shadows is for the plane: --triplanar's box is no flat patch"},
          std::pair{"noise --triplanar 1 --defer-shadow-walks", "--defer-shadow-walks is for the plane"},
          std::pair{"decals --pillar --texel-shadows", "--texel-shadows is for the wall: --pillar's column"},
          std::pair{"decals --pillar --defer-shadow-walks", "--defer-shadow-walks is for the wall: --pillar's column"},
          std::pair{"noise --pillar", "--pillar is for the decals scene: the noise scene"},
          std::pair{"water --camera-elevation 30", "--camera-elevation is for the decals, planet, noise and maps scenes"},
          std::pair{"water --camera-distance 3", "--camera-distance is for the decals, planet, noise and maps scenes"},
          std::pair{"decals --camera-target 1,2", "--camera-target: At least 3 required"},
          std::pair{"decals --camera-height 20", "--camera-height is for the water scene: the decals scene"},
          std::pair{"planet --field 64 --spin-up 0 --camera-target 0,0,-0.5 --camera-distance 1.2",
                    "the planet's camera would stand 0.76 radii from its centre, inside its cloud tops"},
          std::pair{"bench --camera-turn 10", "--camera-turn is for the scenes' runs: bench draws each scene from one"},
          std::pair{"planet --field 64 --spin-up 0 --camera-target 2,0,0 --camera-distance 1.5 "
                    "--camera-azimuth 90 --camera-elevation 0 --camera-turn 30",
                    "the planet's camera would pass, turning (--camera-turn), 0.50 radii from its centre"},
          std::pair{"decals --camera-target 0,nan,0", "--camera-target: 'nan' is not a finite number"},
          std::pair{"noise --triplanar 1 --tiling clamp --noise-kind simplex --field 64",
                    "SurfaceMaterial.triplanar needs a surface that wraps both ways"}}) {
        const Result other = runDemo(std::string(args) + " --headless");
        EXPECT_NE(other.exitCode, 0) << args;
        EXPECT_NE(other.output.find(message), std::string::npos) << args << "\n" << other.output;
    }
    const Result restated = runDemo("decals --field 64 --technique pom --trace-pass auto --headless --width 64 "
                                    "--height 36 --out " + outputPath("demo_restated"));
    EXPECT_EQ(restated.exitCode, 0) << restated.output;
    const Result waterShots = runDemo("water --shots /no/such/shots.txt --headless");
    EXPECT_NE(waterShots.output.find("/no/such/shots.txt"), std::string::npos) << waterShots.output;
    // NaN passes a range check (it compares false with both bounds): refused by name instead of
    // rendering the default. Infinity too.
    for (const char* option : {"--depth-scale", "--dt", "--lod-threshold", "--wind-speed", "--wind-dir"})
        for (const char* value : {"nan", "inf"}) {
            const Result bad = runDemo(std::string("water --headless ") + option + " " + value);
            EXPECT_NE(bad.exitCode, 0) << option << " " << value;
            EXPECT_NE(bad.output.find(option), std::string::npos) << bad.output;
            EXPECT_NE(bad.output.find(value), std::string::npos) << bad.output;
        }
}

TEST(Demo, HelpListsTheOptions) {
    const Result r = runDemo("--help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* option : {"--headless", "--frames", "--out", "--video", "--export-maps", "--width",
                               "--height", "--dt", "--field", "--technique", "--samples-min", "--samples-max",
                               "--depth-scale", "--lod-threshold", "--seed", "--no-shadows", "--waves",
                               "--wind-speed", "--wind-dir", "--environment", "--shots", "--height-map",
                               "--normal-map", "--color-map", "--no-progress", "--format", "--window-shot", "--surface-format",
                               "--texel-shadows", "--no-texel-shadows", "--trace-pass", "--reversed-z", "--camera-azimuth",
                               "--camera-elevation", "--camera-distance", "--camera-target", "--camera-height", "--camera-turn",
                               "--gl", "--cl-device", "water", "decals", "planet", "maps", "bench"})
        EXPECT_NE(r.output.find(option), std::string::npos) << option;
}

} // namespace
} // namespace hfx::test
