#pragma once
// A replayable list of shots for the decal wall: what a player did, as text, so a headless run
// (or a test) repeats it exactly. One shot per line, '#' starts a comment:
//
//   bullet    FRAME U V          a bullet hole at texcoords (U, V)
//   explosion FRAME U V [SEED]   an explosion there; SEED scatters its debris (default 1)
//   click     FRAME X Y          a click at pixel (X, Y) from the image's top-left: picked
//                                through the camera onto the displaced surface, then a bullet
//
// FRAME counts rendered frames: a shot at frame F is stamped by the update that makes frame F
// and shows from F on (frame 0 is the wall before any update, so shots at 0 land with frame 1).
// Texcoords may lie outside [0,1) (they wrap); pixels must lie inside the image, which only the
// scene can check.
//
// Returns owned values. Thread: any.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace hfx {

struct Shot {
    enum class Kind { Bullet, Explosion, Click };
    Kind kind = Kind::Bullet;
    int frame = 0;
    double a = 0.0, b = 0.0;   ///< U, V or X, Y
    std::uint64_t seed = 1;    ///< explosions only
    int line = 0;              ///< where it was read, for messages
};

/// Throws hfx::Error "NAME:LINE: what is wrong" for an unknown kind, a missing, extra or
/// non-numeric field, a negative frame or a non-finite coordinate. At most 1,000,000 shots.
std::vector<Shot> parseShotList(std::string_view text, const std::string& name = "shots");
/// Reads and parses a file; a missing or unreadable file is an error naming it.
std::vector<Shot> readShotList(const std::string& path);
/// One line in the format above (without the newline): parseShotList reads it back.
std::string formatShot(const Shot& shot);

} // namespace hfx
