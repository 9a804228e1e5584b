// libFuzzer target: bytes as a damage log, what a client joining a game late reads from the
// server's message (DamageLog::load). An accepted log must hold at most its budget of impacts that
// add() would take, stamps that are finite and that DecalMap reads as they are (no NaN, no
// negative size), a clock the heal curves read as finite, and save and load back to the same
// impacts and clock to the bit; anything else must be an hfx::Error.
#include "hfx/compute/DamageLog.h"
#include "hfx/core/Error.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

namespace {

bool sameBits(const hfx::ImpactEvent& a, const hfx::ImpactEvent& b) {
    return std::memcmp(&a.u, &b.u, sizeof a.u) == 0 && std::memcmp(&a.v, &b.v, sizeof a.v) == 0 &&
           std::memcmp(&a.nx, &b.nx, sizeof a.nx) == 0 && std::memcmp(&a.ny, &b.ny, sizeof a.ny) == 0 &&
           std::memcmp(&a.nz, &b.nz, sizeof a.nz) == 0 && std::memcmp(&a.radius, &b.radius, sizeof a.radius) == 0 &&
           a.kind == b.kind && a.seed == b.seed && std::memcmp(&a.time, &b.time, sizeof a.time) == 0 &&
           std::memcmp(&a.strength, &b.strength, sizeof a.strength) == 0;
}

bool finiteStamp(const hfx::BulletHole& h) {
    for (float f : {h.u, h.v, h.radius, h.depth, h.rimHeight, h.rimWidth, h.scorch, h.roughness, h.occlusion,
                    h.scorchReach, h.phase, h.glow})
        if (!std::isfinite(f)) return false;
    return h.radius > 0.0f && h.depth >= 0.0f && h.scorch >= 0.0f && h.glow >= 0.0f;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    hfx::DamageLogConfig config;
    config.budget = 64;
    try {
        const hfx::DamageLog log = hfx::DamageLog::load(in, config, "fuzz");
        if (log.size() > config.budget || !std::isfinite(log.now()) || !std::isfinite(log.healTime()) ||
            !std::isfinite(log.glowTime()))
            __builtin_trap();
        for (const hfx::BulletHole& h : log.stamps())
            if (!finiteStamp(h)) __builtin_trap();
        std::ostringstream out;
        log.save(out, "fuzz");
        std::istringstream back(out.str());
        const hfx::DamageLog again = hfx::DamageLog::load(back, config, "again");
        const double now = log.now(), nowAgain = again.now();
        if (std::memcmp(&now, &nowAgain, sizeof now) != 0) __builtin_trap();
        const auto a = log.events(), b = again.events();
        if (a.size() != b.size()) __builtin_trap();
        for (size_t i = 0; i < a.size(); ++i)
            if (!sameBits(a[i], b[i])) __builtin_trap();
        // What add() takes, after load: the log goes on as any other.
        hfx::DamageLog next = again;
        next.advance(0.5);
        next.add({.u = 0.25f, .v = 0.75f});
        for (const hfx::BulletHole& h : next.stamps())
            if (!finiteStamp(h)) __builtin_trap();
    } catch (const hfx::Error&) {
    }
    return 0;
}
