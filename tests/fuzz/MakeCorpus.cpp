// Writes the fuzzers' seed corpus: small valid height maps in the formats the loader meets
// (8/16-bit PNG and TIFF, float EXR and HDR, 1-4 channels), prefixed with the byte that picks
// their extension in FuzzHeightMap, a few shot lists and a few damage logs.
//   hfx-fuzz-corpus DIR   ->  DIR/heightmap/*, DIR/shots/*, DIR/damage/*
#include "hfx/compute/DamageLog.h"
#include "hfx/tools/ImageFiles.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: hfx-fuzz-corpus DIR\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir / "heightmap");
    std::filesystem::create_directories(dir / "shots");
    std::filesystem::create_directories(dir / "damage");
    struct Seed {
        const char* ext;
        int index, channels;
        OIIO::TypeDesc type;
    };
    const Seed seeds[] = {{".png", 0, 1, OIIO::TypeDesc::UINT8}, {".png", 0, 3, OIIO::TypeDesc::UINT16},
                          {".tif", 1, 2, OIIO::TypeDesc::UINT16}, {".tif", 1, 4, OIIO::TypeDesc::FLOAT},
                          {".hdr", 2, 3, OIIO::TypeDesc::FLOAT},  {".exr", 3, 1, OIIO::TypeDesc::HALF},
                          {".pnm", 4, 1, OIIO::TypeDesc::UINT8},  {".bmp", 5, 3, OIIO::TypeDesc::UINT8}};
    int n = 0;
    for (const Seed& s : seeds) {
        const int w = 5 + n, h = 4 + n % 3;
        std::vector<float> pixels(size_t(w) * h * s.channels);
        for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = float(0.5 + 0.4 * std::sin(double(i) * 0.7));
        const std::string tmp = (dir / ("tmp" + std::string(s.ext))).string();
        auto out = OIIO::ImageOutput::create(tmp);
        if (!out || !out->open(tmp, OIIO::ImageSpec(w, h, s.channels, s.type)) ||
            !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close()) {
            std::fprintf(stderr, "hfx-fuzz-corpus: could not write %s\n", tmp.c_str());
            continue;
        }
        std::ifstream in(tmp, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        std::ofstream seed(dir / "heightmap" / ("seed" + std::to_string(n++)), std::ios::binary);
        seed.put(char(s.index));
        seed << bytes;
        std::filesystem::remove(tmp);
    }
    const char* lists[] = {"bullet 0 0.5 0.5\n", "# volley\nbullet 1 0.25 0.75\nexplosion 2 1.5 -0.5 42\nclick 3 640 360\n",
                           "explosion 10 0.1 0.9\n\n\nbullet 11 1e-3 0.999\n"};
    for (int i = 0; i < 3; ++i) std::ofstream(dir / "shots" / ("seed" + std::to_string(i))) << lists[i];
    // Damage logs as save() writes them: empty, a few impacts of both kinds (one merged), a log
    // whose clock ran on past its heal curves, and the older format (no count line).
    hfx::DamageLog log;
    log.save((dir / "damage" / "seed0").string());
    log.add({.u = 0.25f, .v = 0.5f, .radius = 0.02f});
    log.advance(0.75);
    log.add({.u = 0.7f, .v = 0.1f, .radius = 0.05f, .kind = hfx::ImpactKind::Explosion, .seed = 42});
    log.add({.u = 0.7f, .v = 0.1f, .radius = 0.05f, .kind = hfx::ImpactKind::Explosion, .seed = 43});
    log.save((dir / "damage" / "seed1").string());
    log.advance(600.0);
    log.save((dir / "damage" / "seed2").string());
    std::ofstream(dir / "damage" / "seed3")
        << "hfx-damage 1\nnow 0x1p+3\nimpact bullet 0x1p-2 0x1p-1 0x0p+0 0x0p+0 0x1p+0 0x1p-6 7 0x1p+2 0x1p+0\n";
    std::printf("hfx-fuzz-corpus: wrote %d height maps, 3 shot lists and 4 damage logs to %s\n", n, dir.c_str());
    return 0;
}
