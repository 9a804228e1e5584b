// The texture units, image units, uniform blocks and constants that the shaders and their C++
// side share, named once. Only comments and #defines: the shaders #include this file, and C++ includes the
// same text as hfx/core/Bindings.h (core/CMakeLists.txt copies it there at configure time).
// No unit serves two samplers: the surface program needs HFX_TEXTURE_UNITS texture units in its
// fragment stage (GL 4.5 promises 16; NVIDIA, AMD, Intel and llvmpipe have 32), and
// SurfaceRenderer refuses a context with fewer, naming both numbers.

#ifndef HFX_BINDINGS_GLSL
#define HFX_BINDINGS_GLSL

// Texture units.
#define HFX_UNIT_SURFACE 0        // layer 0's normals and height (s_surface)
#define HFX_UNIT_ALBEDO 1         // layer 0's albedo
#define HFX_UNIT_ENVIRONMENT 2    // water: the sky image it reflects
#define HFX_UNIT_PYRAMID 3        // layer 0's bounds pyramid, as a mip chain (PyramidLayout::MipChain)
#define HFX_UNIT_SURFACE1 4       // layers 1-3's normals and heights (the ocean's cascades)
#define HFX_UNIT_SURFACE2 5
#define HFX_UNIT_SURFACE3 6
#define HFX_UNIT_ALBEDO1 7        // layers 1-3's albedo
#define HFX_UNIT_ALBEDO2 8
#define HFX_UNIT_ALBEDO3 9
#define HFX_UNIT_CHANNELS 10      // layer 0's shading channels (roughness, ambient occlusion)
#define HFX_UNIT_SHADOW_MAP 11    // the light's shadow maps (hfx::ShadowMap's, or an engine's: hfx::ShadowCascades)
#define HFX_UNIT_PYRAMID1 12      // layers 1-3's bounds pyramids, as mip chains (bounded searches): an array
#define HFX_UNIT_PYRAMID2 13
#define HFX_UNIT_PYRAMID3 14
#define HFX_UNIT_TEXEL_SHADOWS 15 // the texel shadows of the light (TexelShadowPass)
#define HFX_UNIT_BEAM_START 16    // the beam prepass's depth per block of pixels
#define HFX_UNIT_RING_PROFILE 17  // planet: its rings' radial profile (hfx::PlanetRings)
#define HFX_UNIT_RING_BEHIND 18   // the rings' draw: a copy of what the frame held behind them
#define HFX_UNIT_RING_SHINE 19    // planet: the light its rings scatter onto it (shade/ringshine.comp)
#define HFX_TEXTURE_UNITS 20      // the table's units: a draw's fragment stage binds at most these

// Image units. GL 4.5 promises 8 (GL_MAX_IMAGE_UNITS), and NVIDIA's driver has exactly 8: its
// compiler refuses a binding of 8 or more (llvmpipe has 32, so nothing here would say so; C++
// static_asserts that every unit below is under HFX_IMAGE_UNITS).
#define HFX_IMAGE_UNITS 8
#define HFX_IMAGE_PYRAMID 0       // layer i's atlas pyramid at HFX_IMAGE_PYRAMID + i (PyramidLayout::Atlas, llvmpipe's)
#define HFX_IMAGE_CELLS 4         // layer 0's level-0 cells' samples (BoundsPass writes them)
// The unit a compute pass writes its one output through, one dispatch at a time, and that no
// program reads: the bounds pass's level (trace/hier/bounds.comp), the texel shadows
// (trace/hier/texelshadows.comp, TexelShadowPass), the beam start (trace/hier/beam.comp, ExactTracer).
#define HFX_IMAGE_PASS_OUTPUT 5
// The bounds pass's (BoundsPass): building one layer's pyramid leaves the tracer's units
// (HFX_IMAGE_PYRAMID + i, HFX_IMAGE_CELLS) as they were.
#define HFX_IMAGE_BOUNDS_FINER 6  // the level it reduces (or the atlas)
#define HFX_IMAGE_BOUNDS HFX_IMAGE_PASS_OUTPUT // the level it writes (or the atlas)
#define HFX_IMAGE_RING_SHINE 7    // the rings' light on their planet, as the renderer builds it (shade/ringshine.comp)

// Shader storage buffers.
#define HFX_BUFFER_DEFERRED_SHADOWS 0 // the light walks a surface draw leaves to the pass after it (trace/hier/deferred.glsl)
#define HFX_BUFFER_TRACE_RAYS 1       // the exact tracer's walks in a compute pass: a ray, then its hit, per pixel (trace/hier/trace.glsl)
#define HFX_BUFFER_TRACE_INFO 2       // ... and what goes with it
#define HFX_BUFFER_TRACE_LIGHTS 3     // ... and its light ray, where the light is not one for the draw (a curved mesh, a silhouette fade)

// Uniform blocks.
#define HFX_BLOCK_SURFACE 0       // HfxSurface: hfx::SurfaceUniforms
#define HFX_BLOCK_WATER 1         // HfxWater: the water's look
#define HFX_BLOCK_RINGS 2         // HfxRings: hfx::RingUniforms (the water's impact rings)
#define HFX_BLOCK_PLANET 3        // HfxPlanet: hfx::PlanetUniforms (a planet's rings and their shadows)
#define HFX_BLOCK_SHADOWS 4       // HfxShadows: hfx::ShadowUniforms (the light's shadow maps a draw receives)

// The exact tracer's beam start: its prepass walks one ray per block of this many pixels on
// each axis (ExactTracer, trace/hier/beam.comp) and the draw reads the block's depth.
#define HFX_BEAM_BLOCK 8

// The water sky's clouds (shade/sky.glsl, hfx::cloudSample): the octaves of their value noise,
// and the variance of one octave at a random point (measured over 2^22 points), which sets how
// far an edge softens where the octaves finer than a pixel fade to their mean.
#define HFX_CLOUD_OCTAVES 6
#define HFX_CLOUD_OCTAVE_VARIANCE 0.04607
// How far up the sun's ray (cloud heights) a clouded point's direct light is taken to have come
// through the cloud, and how much of it the cloud there takes where it is whole: a cloud's sunlit
// side is bright, its far side grey (hfx::cloudSunwardStep, once a draw; shade/sky.glsl's
// hfx_cloud_color).
#define HFX_CLOUD_DEPTH 0.3
#define HFX_CLOUD_SUNWARD_SHADE 0.6
// The sun's angular radius (the Sun's from the Earth), radians: the clouds' shadows' penumbra.
#define HFX_SUN_RADIUS 0.00465

#endif
