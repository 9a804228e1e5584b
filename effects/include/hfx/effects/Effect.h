#pragma once
// What a user of the module drives each frame. An effect holds a source of its own concrete
// type and a SurfacePipeline beside it; a frame reads top-down:
//
//   Effect::update(dt)
//     surface.begin(Staged)
//     advance(dt)          the effect: its source steps (storms, stamps, wind... first)
//     enqueueSurface()     the effect: surface.derive(source.buffer()), its passes, surface.submit()
//     surface.finish()     the texels reach GL
//
// then the caller draws textures() with a SurfaceRenderer and material(). beginUpdate(dt) is the
// same with nothing waited for, endUpdate() the finish: draw between the two and the compute
// hides behind the draw.
//
// The material is the effect's, and the one owner of the relief's depth: the surface's normals
// are made once for a fixed depth and rescaled by the renderer, so changing the depth (or any
// other field) is setMaterial() and nothing else.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <string>

namespace hfx {

class Effect {
public:
    virtual ~Effect() = default;
    Effect(const Effect&) = delete;
    Effect& operator=(const Effect&) = delete;

    /// Advances the effect by dt seconds (> 0, finite) and refreshes its textures; each stage
    /// is waited for and timed (lastTimes()). A bad dt throws and changes nothing.
    void update(double dt);
    /// Overlapped frames: enqueues the next frame on the compute device and returns at once
    /// (finishing one still in flight first).
    void beginUpdate(double dt);
    /// Waits for the frame beginUpdate() started and hands it to GL (nothing when none is).
    void endUpdate();

    /// The textures to draw now (they change after each update: ask every frame).
    const SurfaceTextures& textures() const { return surface().textures(); }
    /// What to draw: SurfaceRenderer::draw's layers. One, textures() with the bounds the pipeline
    /// builds for them, for most effects; the ocean's cascades for the ocean.
    virtual std::vector<SurfaceLayer> layers() const {
        return {{.textures = &textures(), .bounds = surface().bounds()}};
    }
    const SurfaceMaterial& material() const { return material_; }
    /// Replaces the material; throws hfx::Error naming the bad field and changes nothing.
    void setMaterial(const SurfaceMaterial& material);
    /// The last frame's stage times, over all the effect's surfaces.
    StageTimes lastTimes() const;
    TransferPath transferPath() const { return surface().transferPath(); }
    /// How the surface reaches GL, for start-up reports: "float16 texels, pixel-buffer path".
    std::string transferDescription() const { return surface().transferDescription(); }

protected:
    explicit Effect(const SurfaceMaterial& material);
    /// The effect's pipeline (a member of the derived class, constructed after its source).
    virtual const SurfacePipeline& surface() const = 0;
    /// All its pipelines, surface() first: an effect with several (the ocean's cascades) lists
    /// them, and the frame begins and finishes each.
    virtual std::vector<const SurfacePipeline*> surfaces() const { return {&surface()}; }
    /// Moves the source on by dt seconds, refusing a bad dt before anything changes.
    virtual void advance(double dt) = 0;
    /// Enqueues this frame's surface from what the source holds now: surface().derive(), the
    /// effect's passes, surface().submit().
    virtual void enqueueSurface() = 0;
    /// The surface of the source as it is now, synchronously, without advancing it: what a
    /// constructor calls once, and what a jump in time or a new spectrum calls.
    void refresh();

    SurfaceMaterial material_;

private:
    void begin(StageTiming timing);
    void finish();
};

} // namespace hfx
