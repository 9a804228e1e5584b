#pragma once
// The rings' light on their planet (shaders/shade/ringshine.comp): a table of the irradiance the
// sunlight scattered by a planet's rings brings to each point of its cloud tops, by latitude and
// by longitude from the sun's meridian, which the planet's shading reads (hfx_ring_shine). It
// depends on the rings' profile and radii and on the sun's elevation over their plane only, so
// it is made again only where one of those changes (a planet that turns, or moves, keeps it);
// the tables of the last kTables such keys are kept (several ringed planets, each under its own
// sun, each keep theirs). SurfaceRenderer owns one.
//
// Owns its textures and program. Thread: the thread whose GL context is current.

#include "hfx/core/GlObject.h"
#include "hfx/core/ShaderProgram.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace hfx {

class RingShine {
public:
    /// The table's size: longitudes, latitudes; the elements its integral sums over the rings.
    static constexpr int kLongitudes = 32, kLatitudes = 32, kRadial = 32, kAround = 64;
    static constexpr size_t kTables = 4;

    /// The table for rings of radial profile `profile` (PlanetLook::ringProfile) from `inner` to
    /// `outer` planet radii, the sun at `sinElevation` over their plane (towards the side their
    /// axis points to where positive), made where one of those changed. Changes the current
    /// program, texture unit HFX_UNIT_RING_PROFILE and image unit HFX_IMAGE_RING_SHINE: call
    /// inside a GlStateGuard.
    GLuint texture(GLuint profile, float inner, float outer, float sinElevation);

private:
    struct Key {
        GLuint profile = 0;
        float inner = 0.0f, outer = 0.0f, sinElevation = 0.0f;
        bool operator==(const Key&) const = default;
    };
    struct Table {
        Key key;
        std::uint64_t used = 0; ///< 0: never made
        GlTexture texture;
    };
    std::array<Table, kTables> tables_{};
    std::uint64_t clock_ = 0;
    std::optional<ShaderProgram> program_;
};

} // namespace hfx
