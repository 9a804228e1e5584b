// libFuzzer target: bytes as an image file (the first byte picks the extension the codec
// guesses from) through the height-map path: readImage with its limits, then heightsFromImage.
// Any hfx::Error is a correct refusal; a crash, a sanitizer report or an escaped exception of
// another type is a finding.
#include "hfx/core/Error.h"
#include "hfx/tools/ImageFiles.h"
#include "hfx/core/SurfaceMaps.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const char* extensions[] = {".png", ".tif", ".hdr", ".exr", ".pnm", ".bmp"};
    const std::string path = "/tmp/hfx-fuzz-" + std::to_string(getpid()) + extensions[data[0] % 6];
    {
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    }
    try {
        // Small limits: the fuzzer should find refusals, not spend its time on huge allocations.
        const hfx::Image image = hfx::readImage(path, {.maxPixels = 1 << 20});
        const std::vector<float> heights = hfx::heightsFromImage(image, path);
        if (heights.size() != size_t(image.width) * image.height) __builtin_trap();
        for (float h : heights)
            if (!(h >= 0.0f && h <= 1.0f)) __builtin_trap(); // accepted heights lie in [0,1]
    } catch (const hfx::Error&) {
    }
    std::remove(path.c_str());
    return 0;
}
