#pragma once
// A procedural brick wall for the decal user when no maps are given: running-bond bricks with
// bevelled edges, per-brick tilt and colour, a rough face and recessed mortar. Tileable: the
// pattern repeats exactly across the map's edges, so stamps and texcoords may wrap.
//
// Returns owned maps. Thread: any; no GL or CL calls.

#include "hfx/core/Image.h"

#include <cstdint>
#include <vector>

namespace hfx {

struct BrickWallConfig {
    int size = 512;             ///< texels per edge (square), >= 64
    int rows = 8;               ///< brick courses per tile (even, so the running bond tiles)
    int bricksPerRow = 4;
    float mortarHeight = 0.45f; ///< the joints' height; brick faces sit near 0.92
    std::uint64_t seed = 7;
    void validate() const;
};

struct BrickWallMaps {
    std::vector<float> heights; ///< size*size in [0,1], row 0 at v = 0
    Image albedo;               ///< size x size RGB, top row first (as images are stored)
};

BrickWallMaps makeBrickWall(const BrickWallConfig& config = {});

} // namespace hfx
