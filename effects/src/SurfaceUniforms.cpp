#include "hfx/effects/SurfaceUniforms.h"

#include "hfx/core/Error.h"
#include "hfx/core/SurfaceTextures.h"

#include <algorithm>

namespace hfx {

void describePyramid(SurfaceUniforms& u, const SurfaceTextures& textures) {
    u.pyramidLevels = textures.pyramidLevels();
    if (u.pyramidLevels > kMaxPyramidLevels)
        throw Error(str("describePyramid: ", u.pyramidLevels, " pyramid levels, the shaders hold ", kMaxPyramidLevels));
    const int width = textures.config().width, height = textures.config().height;
    for (int level = 0; level < u.pyramidLevels; ++level) {
        const auto [x, y] = SurfaceTextures::pyramidAtlasOrigin(width, height, level);
        u.pyramidLevel[level] = {x, y, std::max(width >> level, 1) - 1, std::max(height >> level, 1) - 1};
    }
}

} // namespace hfx
