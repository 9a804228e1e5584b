#pragma once
// What a user of the module drives each frame: update(dt) produces this frame's height field on
// the compute device, derives its normals and hands both to GL; the caller then draws with a
// SurfaceRenderer using textures() and material().
//
// An effect owns its source, compute buffers and textures. Thread: the thread that owns both
// the ClContext and the current GL context.

#include "hfx/core/SurfaceTextures.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <string>

namespace hfx {

/// Wall-clock milliseconds of the last update, by stage (measured on the host around waits).
struct StageTimes {
    double compute = 0.0; ///< field step + normals (+ pyramid, colours), enqueue to finish
    double upload = 0.0;  ///< map, GL upload, mip generation
    // The parts of compute, each waited for on its own (so they add up to compute):
    double field = 0.0;   ///< the source's step
    double normals = 0.0; ///< Sobel
    double extra = 0.0;   ///< the height pyramid and effect-specific work (colours, normal map)
    // After beginUpdate/endUpdate (overlapped), the parts are not waited for one by one: compute
    // is then the time endUpdate() still had to wait, the part the draw did not hide.
};

class Effect {
public:
    virtual ~Effect() = default;
    /// Advances the effect by dt seconds (> 0) and refreshes its textures.
    virtual void update(double dt) = 0;
    /// Overlapped frames: beginUpdate(dt) enqueues the next field on the compute device and
    /// returns at once; endUpdate() waits for it and hands it to GL. Draw the current textures()
    /// between the two and the compute hides behind the draw. update(dt) is the two in a row.
    virtual void beginUpdate(double dt) { update(dt); }
    virtual void endUpdate() {}
    virtual const SurfaceTextures& textures() const = 0;
    virtual const SurfaceMaterial& material() const = 0;
    virtual StageTimes lastTimes() const = 0;
    /// How the surface reaches GL, for start-up reports: "float16 texels, pixel-buffer path".
    virtual std::string transferDescription() const = 0;
};

} // namespace hfx
