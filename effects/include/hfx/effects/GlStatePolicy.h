#pragma once
// What HFX's draws and passes do with the GL state they change (SurfaceRenderer, PlanetRings,
// SurfacePipeline's texel shadows), on the calling thread's GL context.
//
// - Restore (the default): each reads the state it will change first (about 120 queries a
//   surface draw: its texture, image, buffer and block bindings, its depth and cull state, its
//   masks) and puts it back, so the caller's state survives; it also checks the clip control and
//   a motion or normal target against the camera.
// - Defaults: each reads no state it changes and leaves GL's defaults in it afterwards (no
//   program, vertex array, texture, sampler, image, storage or uniform buffer bound on the
//   bindings HFX uses, texture unit 0 active, the depth test and face culling off with GL_LESS,
//   GL_BACK and GL_CCW, the depth and colour masks on, program point size off), and makes none of
//   the checks above (a wrong clip control or target draws wrongly, unreported). For an engine
//   that tracks its own state and binds what it needs before each draw: a query of GL state waits
//   for the driver where it runs GL on a thread of its own (NVIDIA's threaded optimisation), so a
//   normal-mapped, POM or sky draw then asks nothing of it. What a draw still reads: its colour
//   target's format where the colour output is ColorOutput::Auto (set Display or Linear not to);
//   where the exact tracer draws passes of its own (the beam start, the compute pass) what it
//   draws back into (the framebuffer, the viewport, blending, the scissor and stencil tests, the
//   masks); a pass inside a draw (the texel shadows, redrawn where the field or the light
//   changed) saves and puts back what the draw had bound; PlanetRings the frame it composes
//   over. docs/API.md lists the state each call changes; tests/GlStateTest.cpp counts.
//
// Thread: the thread whose GL context is current; each thread holds its own policy.

namespace hfx {

enum class GlStatePolicy { Restore, Defaults };

/// Sets the calling thread's policy for the draws and passes that follow.
void setGlStatePolicy(GlStatePolicy policy);
/// The calling thread's policy (Restore until set).
GlStatePolicy glStatePolicy();

} // namespace hfx
