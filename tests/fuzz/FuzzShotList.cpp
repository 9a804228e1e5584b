// libFuzzer target: bytes as a shot list. Accepted lists must format and parse back to the same
// shots; anything else must be an hfx::Error.
#include "hfx/core/Error.h"
#include "hfx/tools/ShotList.h"

#include <cmath>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const std::vector<hfx::Shot> shots = hfx::parseShotList(text, "fuzz");
        std::string again;
        for (const hfx::Shot& s : shots) {
            if (s.frame < 0 || !std::isfinite(s.a) || !std::isfinite(s.b)) __builtin_trap();
            again += hfx::formatShot(s) + "\n";
        }
        const std::vector<hfx::Shot> back = hfx::parseShotList(again, "again");
        if (back.size() != shots.size()) __builtin_trap();
        for (size_t i = 0; i < shots.size(); ++i)
            if (back[i].kind != shots[i].kind || back[i].frame != shots[i].frame || back[i].a != shots[i].a ||
                back[i].b != shots[i].b)
                __builtin_trap();
    } catch (const hfx::Error&) {
    }
    return 0;
}
