#pragma once
// Draws a mesh with a height-field surface, by any technique of the table (Technique.h) and any
// shading model: the program is composed from shaders/surface.frag, the technique's trace file
// and the model's shade file, built per variant on first use and kept. Per-draw uniforms go in
// one uniform buffer (SurfaceUniforms). It draws into whatever framebuffer and context the
// caller has bound and restores the GL state it changes (program, vertex array, depth test, face
// culling and winding, the texture units, image units, uniform-buffer and storage-buffer bindings
// of Bindings.h; around the computed walks' rays draw, every draw buffer's colour mask and the
// depth mask). What the exact tracer reads besides the surface textures, and when it is made, is
// its ExactTracer's (tracer/ExactTracer.h).
//
// Thread: the thread whose GL context is current.

#include "hfx/core/Bindings.h"
#include "hfx/core/Camera.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/ShaderProgram.h"
#include "hfx/core/SurfaceTextures.h"
#include "hfx/effects/Picking.h"
#include "hfx/effects/RingShine.h"
#include "hfx/effects/ShadowCascades.h"
#include "hfx/effects/SurfaceUniforms.h"
#include "hfx/effects/Technique.h"
#include "hfx/effects/tracer/ExactTracer.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <string>

namespace hfx {

/// The sky a water look draws and reflects (WaterLook::sky(); HFX_SKY, a define of the program:
/// on a CPU rasteriser a branch on a uniform runs both sides, and the clouds' noise would cost
/// every water pixel where there are none: llvmpipe's clear-sky POM draw 1.10-1.12x, its sky pass
/// 1.7x, docs/BENCHMARKS.md; a GPU pays only a program per kind).
enum class SkyKind {
    Gradient = 0,    ///< skyZenith to skyHorizon with the sun's glow
    Clouds = 1,      ///< the same with clouds (cloudCover > 0)
    Environment = 2, ///< an equirectangular image (environment)
};

/// The water look (Shading::Water). Colours are linear RGB.
/// One ring of waves on the water, in the mesh's texcoords: h += amplitude exp(-(x/width)^2)
/// cos(wavenumber x) with x = r - radius, r the distance from the centre; foam on its crest.
struct WaterRing {
    glm::vec2 centre{0.0f};
    float radius = 0.0f;
    float width = 1.0f;
    float wavenumber = 0.0f; ///< radians per texcoord
    float amplitude = 0.0f;  ///< height units (fractions of the material's depth)
    float foam = 0.0f;       ///< coverage on the crest, 0..1
    bool operator==(const WaterRing&) const = default;
};

struct WaterLook {
    glm::vec3 deepColor{0.004f, 0.035f, 0.07f};    ///< troughs: light travels far in the water
    glm::vec3 shallowColor{0.02f, 0.16f, 0.17f};   ///< crests: thin water scatters the sun
    glm::vec3 skyZenith{0.12f, 0.3f, 0.65f};       ///< procedural sky, used without environment
    glm::vec3 skyHorizon{0.62f, 0.72f, 0.82f};
    float fresnelF0 = 0.02f;                       ///< reflectance of water seen head-on
    float glintPower = 900.0f;                     ///< sharpness of the sun's reflection
    float glintStrength = 40.0f;
    float hazeDistance = 90.0f;                    ///< world units where half the colour is haze
    float sunGlow = 0.6f;                          ///< the glow around the sun in the procedural sky
    /// Crests lit from behind glow in shallowColor: sunlight crossing a wave's thin top towards
    /// the eye; and the faces of the waves, dimmer, with the light the water scatters out towards
    /// an eye that looks towards the sun at a grazing angle (shaders/shade/water.glsl). 0: none;
    /// 1 lights a crest two sigma of the sea high, seen against the sun, with six times the
    /// shallow colour.
    float translucency = 1.0f;
    /// The albedo's alpha is foam coverage and its red the young part of it (OceanEffect writes
    /// them per cascade): foam is drawn in foamColor, lit like snow, and widens the glint by
    /// foamRoughness. Young foam (a breaking crest's) is dense; as it ages it opens into a lace
    /// of bubbles foamCells to the texcoord (OceanEffect: from OceanEffectConfig::foamCellMeters,
    /// 0.5 m; 0 draws no lace) that thins as the coverage falls, and every foam's edge frays
    /// through the same bubbles.
    bool foam = false;
    float foamCells = 0.0f;
    glm::vec3 foamColor{0.9f, 0.93f, 0.95f};
    float foamRoughness = 0.6f;
    /// Wind streaks (spindrift, shade/water.glsl): foam drawn out downwind into long bands,
    /// `spindrift` their strength (0: none; OceanEffect sets it from the wind: 0 up to the middle
    /// of Beaufort 7, 1 from that of 10, times how far its foam has built), windDirection where the
    /// wind blows in texcoords (unit), streakCells the streaks' lattice cells per texcoord across
    /// the wind (OceanEffect: one per 3 m; a band is 0.2 to 0.6 of a cell wide). They ride with the
    /// foam: foamDrift (texcoords) is how far it has drifted downwind (OceanEffect moves it every
    /// step). Over a wind change the last wind's streaks fade out where they lie, spindriftFrom
    /// their strength and windDirectionFrom their direction, as the new wind's fade in (OceanEffect
    /// blends them as the waves are): turned at once, the lines swung about the texcoords' origin.
    glm::vec2 foamDrift{0.0f};
    float spindrift = 0.0f;
    glm::vec2 windDirection{1.0f, 0.0f};
    float streakCells = 0.0f;
    float spindriftFrom = 0.0f;
    glm::vec2 windDirectionFrom{1.0f, 0.0f};
    /// Optional equirectangular sky (a GL texture the caller owns; 0 = procedural sky).
    unsigned environment = 0;
    /// Clouds in the procedural sky (shade/sky.glsl; hfx::skyColor, hfx::cloudSample and
    /// hfx::cloudSunlight give the same on the CPU): a layer of them `cloudHeight` world units over
    /// the world's y = 0 (the water's level; metres for the ocean), lit by the sun (greyer where
    /// thick and on the side away from the sun, a silver edge towards it), drawn by drawSky,
    /// reflected by the water, their shadows dimming the sun's light on the water. Towards the
    /// horizon the layer, seen edge on, fades into its mean, which the haze takes: under a cover
    /// near 1 the horizon and the far sea are the clouds' grey, not the clear sky's blue.
    /// `cloudCover` is the share of the sky overhead under a cloud's middle, 0 (none, the default)
    /// to 1; `cloudScale` the clouds per cloud height (larger: smaller clouds; about one per
    /// 1,000 m at 1,500 m is 1.5); `cloudDrift` how far the layer has moved, in cloud heights
    /// along world x and z (the caller moves it: the wind aloft over the clouds' height, per
    /// second). Not with an environment image, which is the whole sky.
    float cloudCover = 0.0f;
    float cloudScale = 1.5f;
    float cloudHeight = 1500.0f;
    glm::vec2 cloudDrift{0.0f};
    /// Rings of waves spreading from impacts (OceanEffect::disturb fills them each frame), added
    /// to the traced height, the slopes and the foam: not tiled with the sea's patches.
    std::array<WaterRing, kMaxWaterRings> rings{};
    int ringCount = 0;
    /// Which sky the look draws: its environment image, else the gradient with clouds where
    /// cloudCover > 0, else the gradient alone.
    SkyKind sky() const;
    /// Throws hfx::Error naming the field, for what the sky reads: an environment that is not a
    /// GL texture, a cloudCover outside [0, 1], a cloudScale outside (0, 64], a cloudHeight not
    /// positive and finite, a cloudDrift not finite, clouds with an environment image
    /// (SurfaceMaterial::validate checks the rest).
    void validateSky() const;
    bool operator==(const WaterLook&) const = default;
};

/// The planet look (Shading::Planet): its rings, whose shadow falls on the cloud tops
/// (shaders/shade/rings.glsl; PlanetRings::look() fills it). Lengths are in the mesh's model units:
/// the planet is the sphere of `radius` about the model's origin, and the rings lie in the
/// model's xz plane (makeSphere's equator), under a model matrix that scales uniformly.
struct PlanetLook {
    float radius = 1.0f;               ///< the planet's (makeSphere's radius)
    float ringInner = 0.0f;            ///< from the centre, beyond radius
    float ringOuter = 0.0f;            ///< 0: no rings
    float sunAngularRadius = 0.00465f; ///< radians, the sun's disc (the Sun's from Earth): the shadows' penumbrae
    /// The rings' radial profile (a GL texture the caller owns, PlanetRings'): one row of RGBA
    /// texels from ringInner to ringOuter, rgb the particles' albedo, a the opacity seen along
    /// the rings' normal, with mips and a border of 0.
    unsigned ringProfile = 0;
    /// The sunlight the rings scatter lights the planet (the renderer integrates it over the
    /// rings, RingShine): what lights the night side under their lit face.
    bool ringShine = true;
    void validate() const; ///< throws hfx::Error naming the field and its value
    bool operator==(const PlanetLook&) const = default;
};
/// The HfxPlanet block of `look` for a planet drawn with `model`: its centre, radius and rings in
/// world space.
PlanetUniforms planetUniforms(const PlanetLook& look, const glm::mat4& model);

/// Triplanar mapping (SurfaceMaterial::triplanar): the texcoords from the mesh's own position
/// instead of its texcoords, for meshes whose texcoords do not suit a tiled relief or that have
/// none (rocks, cliffs, props; a sphere without its poles' pinch). Each of the mesh's three axes
/// projects the position onto the other two, x onto (y, z), y onto (x, -z) (makePlane's
/// texcoords, up to a whole number of repeats), z onto (x, y), u turned on the faces towards an
/// axis's negative side so that none reads the texture mirrored. The projections whose weight
/// is not 0 each trace and shade the pixel in their own frame (dP/du and dP/dv along the surface
/// as the projection runs), and the colours, traced points (depth, motion) and deferred outputs
/// blend by weight: max(|n_axis| - 0.3, 0)^sharpness of the mesh's own unit normal, normalised.
/// A face within 17 degrees of an axis (its normal's other components under 0.3) takes that
/// projection alone, one trace; where two or three blend, the pixel costs two or three, and its
/// traced point (its depth) is their points' weighted mean. The
/// texture must tile (wrap both ways). The exact tracer walks in the draw (no compute pass, texel
/// shadows or beam start: those follow a flat patch's texcoords). pickMesh picks in the heaviest
/// projection's frame.
struct TriplanarMapping {
    float scale = 0.0f;     ///< texcoords (texture repeats) per unit of the mesh's own space; 0: off
    float sharpness = 4.0f; ///< the weights' power, 1 to 64: the higher, the narrower the blends
    bool on() const { return scale > 0.0f; }
    bool operator==(const TriplanarMapping&) const = default;
};

struct SurfaceMaterial {
    float depthScale = 0.05f;    ///< texture units between h = 1 and h = 0
    int minSamples = 8;          ///< linear-search steps seen head-on
    int maxSamples = 50;         ///< ... at grazing angles
    float lodThreshold = 4.0f;   ///< mip level where POM has faded to normal mapping
    bool shadows = true;
    int shadowSamples = 8;
    float shadowSharpness = 2.0f;
    bool clipToPatch = false;    ///< discard rays that leave patchBounds (finite patches)
    glm::vec4 patchBounds{0, 0, 1, 1};
    float specularStrength = 0.4f;
    float specularPower = 48.0f;
    Shading shading = Shading::Lit;
    WaterLook water;
    PlanetLook planet;
    /// Curved meshes: the relief fades out where the view grazes the geometry (cos below this),
    /// so silhouettes keep the mesh's outline instead of smearing texels. 0 = off.
    float silhouetteFade = 0.0f;
    /// The effort picked from the screen, in pixels (0 = full effort). The exact tracer
    /// (Technique::Hierarchical) stops at the first pyramid cell that surely holds the hit within
    /// that screen error (the ray leaves the cell below the cell's lowest height soon enough)
    /// instead of solving level 0; the point it returns is never below the surface. The sampled
    /// tracers take no more search and shadow steps than keep each step within it on the screen
    /// (at most the samples above): a bound on the step, not on their error. Less work where the
    /// relief is small on the screen (far away, seen from above).
    float pixelBudget = 0.0f;
    /// Bound the sampled searches (pom, secant, relief, steep) by the height pyramid, where every
    /// traced layer can carry one (HeightBounds: power-of-two sizes, a float format; the exact
    /// tracer builds them each frame the heights change): each ray steps only through the depths
    /// the heights on its path reach (four pyramid fetches per layer give them), and each shadow
    /// ray only below their top, with steps no longer than without. It pays where rays take many
    /// steps through a relief whose range along them is small against its depth (the ocean's
    /// cascades: OceanEffect sets it); on a single map with large texels the four fetches cost what
    /// they save.
    bool boundedSearch = false;
    /// The texcoords from the mesh's position projected along its axes (TriplanarMapping; off by
    /// default): with one layer, and not with clipToPatch.
    TriplanarMapping triplanar;
    void validate() const; ///< throws hfx::Error naming the field and its value
    bool operator==(const SurfaceMaterial&) const = default;
};

/// A shader source of the module by its path under shaders/ ("trace/pom.glsl"): the embedded
/// copy, or the file in HFX_SHADER_DIR when that is set. For harnesses that run a tracer outside
/// the renderer (shaders/trace/README.md). Throws hfx::Error for an unknown name.
SourceFile surfaceShader(std::string_view name);
/// A stage of the module's shaders composed from its top file ("surface.frag"), its #include
/// lines expanded through surfaceShader (expandIncludes); `slots` names the files of its
/// `#include <slot>` lines (surface.frag's <tracer> and <shading>).
std::vector<SourceFile> surfaceStage(std::string_view top, const std::map<std::string, std::string, std::less<>>& slots = {});

class ShadowMap;

struct DirectionalLight {
    glm::vec3 direction{0.4f, 0.6f, 0.3f}; ///< towards the light, need not be unit length
    glm::vec3 color{1.0f, 0.97f, 0.9f};
    glm::vec3 ambient{0.18f, 0.2f, 0.24f};
    /// Optional: the light's shadow map (drawn this frame by the caller); surfaces and lit flat
    /// meshes drawn under this light receive its shadows (a map never fitted is refused by name).
    /// The caller keeps it alive.
    const ShadowMap* shadowMap = nullptr;
    /// Optional, in place of shadowMap: the light's shadow maps of an engine's own (its cascades,
    /// drawn this frame), received the same way. The caller keeps them alive.
    const ShadowCascades* cascades = nullptr;
    /// Throws hfx::Error naming the field: a direction not finite or zero (it is normalised for
    /// the shaders), a colour or ambient not finite or negative, both shadowMap and cascades set.
    void validate() const;
};

/// The light as the exact tracer's shadow rays see it on a flat surface: its texture frame in
/// world space (SurfaceFrame::ofPlane for a makePlane mesh and its model matrix), the light and
/// the material, as shaders/surface.frag derives each ray (flatPatchLight: of a flat mesh). Empty
/// where no shadow ray is traced (the light at or below the surface's plane, no self-shadows, no
/// depth).
std::optional<ShadowLight> flatSurfaceLight(const SurfaceFrame& frame, const DirectionalLight& light,
                                            const SurfaceMaterial& material);

/// One layer of a layered surface (the ocean's cascades): its textures, read at the mesh's
/// texcoords times `texcoordScale`, contributing `weight` of the height (h = sum weight_i h_i,
/// the weights summing to 1) and, through it, of the slopes. Layers must tile (wrap both ways).
/// An untraced layer only shades: the tracers see it flat at `restHeight` (its mean), which
/// saves its fetch at every search and shadow step; worth it where weight * its height's range
/// is a few percent of the depth or less. Traced layers come first; layer 0 is always traced.
struct SurfaceLayer {
    const SurfaceTextures* textures = nullptr;
    float texcoordScale = 1.0f;
    float weight = 1.0f;
    bool traced = true;
    float restHeight = 0.5f;
    /// The textures' height bounds where their producer builds them (SurfacePipeline::bounds:
    /// the compute device's, GlWorkarounds::pyramidFromCompute); the exact tracer reads them
    /// where they hold the current texels in the draw's layout, and builds its own otherwise.
    /// null: it always builds its own.
    HeightBounds* bounds = nullptr;
};
inline constexpr int kMaxSurfaceLayers = 4;

/// How the colours a draw writes are encoded (SurfaceRenderer::setColorOutput, PlanetRings').
enum class ColorOutput {
    /// By the bound draw framebuffer's colour buffer at each draw: Linear for a float one, or for
    /// an sRGB one with GL_FRAMEBUFFER_SRGB enabled (GL encodes what is written); else Display.
    Auto,
    /// Clamped to [0, 1] and encoded with gamma 2.2: display values for a plain 8-bit target.
    Display,
    /// Linear radiance, unclamped (up to 65504, a half float's largest): for an engine's HDR
    /// target, its exposure and tone mapping (the sun's glint on ColorOutputTest's sea reaches
    /// 34.6).
    Linear,
};

/// The draw buffers a deferred engine's lighting reads from a surface draw
/// (SurfaceRenderer::setSurfaceOutputs): each 1 to 7, 0 for none. Written for every pixel of a
/// camera's surface draw, at the traced point, beside its forward-shaded colour in buffer 0; the
/// sky, flat meshes and the rings write none of them.
struct SurfaceOutputs {
    /// The relief's world-space unit normal (xyz), and the variance of the slopes the pixel covers
    /// (w: Toksvig's, for the engine's specular anti-aliasing). A float or signed normalized
    /// target (a draw refuses another by name).
    int normal = 0;
    /// The albedo, linear (rgb), and its alpha (a: an effect's foam coverage where it writes one).
    int albedo = 0;
    /// The shading channels: roughness (r), ambient occlusion (g, 1 open), the share of the
    /// draw's light that reaches the point (b, 1 lit): the relief's self-shadow (hier's walked,
    /// POM's soft) times, on water under clouds, the clouds' shadow (WaterLook::cloudCover); the
    /// light's shadow map not in it. And the height (a, 1 at the polygon).
    int material = 0;
    /// The light the point emits itself, linear RGB (rgb; a 1): the shading channels' heat as
    /// embers (a fresh crater's glow) under the lit model, none on the water and the planet. The
    /// engine adds it to its lighting. A float target (a normalized one, which would clamp it at
    /// 1, is refused by name).
    int emission = 0;
    auto operator<=>(const SurfaceOutputs&) const = default;
};

struct DrawOptions {
    Technique technique = Technique::ParallaxOcclusion;
    bool traceOutput = false; ///< write (u, v, depth fraction, fetches) to draw buffer 1, the entry's uv to 2
    /// The exact tracer's beam start: before a hier draw of a flat patch (a camera's or
    /// drawShadow's; Mesh::flatPatch, one layer, no silhouette fade) a prepass walks one ray per
    /// block of kBeamBlock x kBeamBlock pixels against the pyramid's maxima widened to cover the
    /// block's rays, and the draw's rays start where it found the block's first possible hit:
    /// the same hits, fewer steps at grazing angles (16-46% of the view walk's fetches at 45-80
    /// degrees on llvmpipe). false: every ray walks from the top.
    bool beamStart = true;
    /// The exact tracer's texel shadows on a flat patch (ExactTracer, TexelShadowPass): hier's
    /// self-shadow read from the four samples around the point wherever the hard shadow does not
    /// change between them (the penumbra their bilinear blend; a hard shadow finer than the
    /// samples can be missed), walked elsewhere. Auto: where they pay on this view with the
    /// walks in the draw; not with the walks in a compute pass (a GPU's), where they do not pay.
    TexelShadowChoice texelShadows = TexelShadowChoice::Auto;
    /// With texelShadows On: every texelStride-th sample on each axis (a power of two dividing
    /// the field's size; 0: the policy's stride, or 1).
    int texelStride = 0;
    /// With texel shadows read on a camera's draw: a light ray they do not hold (the hard
    /// shadow's edge crosses its cell) is walked after the draw by a compute pass, one to a
    /// lane, and its pixel written again (ExactTracer::finish), instead of in the draw, where
    /// its warp waits for that one lane's walk. The same pixels. Not with traceOutput, nor for
    /// water (its colour is not affine in the light: shadingAffineInLight), nor where the caller
    /// draws with blending or a stencil test (the pixel is written twice), nor on a context whose
    /// vertex stage reads no storage buffer: those walk in the draw.
    /// Off until a GPU has timed it: what it saves a 32-lane warp is counted, not timed, and the
    /// deferring draw shades those pixels twice and, on AMD's compiler, schedules for 16 waves
    /// a SIMD instead of 18 (64 vector registers against 56); on llvmpipe, no guide to a GPU
    /// here (8 lanes wait for less), it is slower. bench-tracers' 'deferred' column times it
    /// against the walks in the draw (docs/BENCHMARKS.md).
    bool deferShadowWalks = false;
    /// Where the exact tracer walks the view rays (a camera's, a shadow caster's) and their light
    /// rays on a convex mesh (Mesh::convex; one layer, no stencil test, a single-sampled target):
    /// Auto, the device's: the draw where GlWorkarounds::traceInDraw says so, else the faster of
    /// the two on this device, timed on the first draws (TracePassTrial).
    TracePass tracePass = TracePass::Auto;
    /// How the exact tracer holds the height bounds it builds (Auto: the device's; tests and
    /// benches pick one side).
    PyramidLayout boundsLayout = PyramidLayout::Auto;
    /// The mesh's model matrix at the previous frame, for the screen motion the draw writes
    /// (SurfaceRenderer::setMotionOutput): a traced point moves as the mesh carries it. Empty:
    /// this frame's (the mesh stood still).
    std::optional<glm::mat4> previousModel;
};

/// The side of the beam start's blocks, in pixels (DrawOptions::beamStart).
inline constexpr int kBeamBlock = HFX_BEAM_BLOCK;

/// What picks a surface program besides DrawOptions: each field is a define of its own, so a
/// switched-off feature costs nothing (on a CPU rasteriser a branch on a uniform still runs its
/// body). draw() derives it from the material, layers and light; program() takes it to build a
/// variant ahead of its first draw.
struct SurfaceVariant {
    Shading shading = Shading::Lit;
    int layers = 1;             ///< HFX_LAYERS
    int traced = 0;             ///< HFX_TRACED_LAYERS (0: all the layers)
    bool selfShadows = true;    ///< HFX_SELF_SHADOW where the technique has them: SurfaceMaterial::shadows
    /// HFX_BOUNDED_SEARCH: SurfaceMaterial::boundedSearch, every traced layer can carry bounds
    bool boundedSearch = false;
    /// HFX_SHADOW_MAP: the light's shadow maps are received, from a 2D texture (1: a ShadowMap, or
    /// ShadowCascades in an atlas) or a 2D array (2); 0: none
    int shadowMap = 0;
    bool rings = false;         ///< HFX_RINGS: water with impact rings (WaterLook::ringCount > 0)
    /// HFX_SKY: the sky the water reflects (and the sky pass draws), WaterLook::sky()
    SkyKind sky = SkyKind::Gradient;
    bool caster = false;        ///< HFX_SHADOW_CASTER: drawing into a shadow map
    /// HFX_TEXEL_SHADOWS: hier's self-shadows with the texel shadows (ExactTracer,
    /// DrawOptions::texelShadows): a ray of their light walks only where the hard shadow changes
    /// between the four samples around its point
    bool texelShadows = false;
    /// HFX_BEAM_START: hier's view rays start at the beam prepass's depth for their block
    /// (DrawOptions::beamStart on a flat patch)
    bool beamStart = false;
    /// HFX_DEFERRED_SHADOWS: with texelShadows, a light ray they do not hold is left to the pass
    /// after the draw (ExactTracer::finish, DrawOptions::deferShadowWalks)
    bool deferredShadows = false;
    /// HFX_COMPUTE_TRACE: 1 for the rays draw of TracePass::Compute, 2 for its shading draw
    /// (trace/hier/trace.glsl); 0: the draw walks its rays
    int computeTrace = 0;
    /// HFX_TRACE_LIGHTS: the rays draw stores each pixel's light ray too (TracerFrame::traceLights)
    bool traceLights = false;
    /// HFX_PYRAMID_ATLAS: the bounds read are in PyramidLayout::Atlas (llvmpipe's workaround,
    /// GlWorkarounds::pyramidAtlas), not mip chains
    bool pyramidAtlas = false;
    /// HFX_REVERSED_Z: the camera's depth is reversed (Camera::reversedZ): the traced depth is
    /// written for GL's [0, 1] clip depth, never nearer (greater) than the polygon's
    bool reversedZ = false;
    /// HFX_MOTION_OUTPUT: the draw buffer the screen motion is written to
    /// (SurfaceRenderer::setMotionOutput); 0: none
    int motionOutput = 0;
    /// HFX_NORMAL_OUTPUT, HFX_ALBEDO_OUTPUT, HFX_MATERIAL_OUTPUT, HFX_EMISSION_OUTPUT: the draw
    /// buffers a deferred engine reads (SurfaceRenderer::setSurfaceOutputs)
    SurfaceOutputs outputs;
    /// HFX_TRIPLANAR: SurfaceMaterial::triplanar is on (not with texel shadows, beam start or
    /// layers; in the compute pass each projection walks in its own plane of slots)
    bool triplanar = false;
    auto operator<=>(const SurfaceVariant&) const = default;
};

class SurfaceRenderer {
public:
    SurfaceRenderer() = default;

    void draw(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
              const SurfaceMaterial& material, const Camera& camera, const DirectionalLight& light,
              const DrawOptions& options = {});
    /// A layered surface: 1 to kMaxSurfaceLayers layers of one surface format, traced as the
    /// sum of their heights (every technique but hier, which needs one grid) and shaded with the
    /// sum of their slopes. The material's depthScale is in the mesh's texcoords.
    void draw(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
              const SurfaceMaterial& material, const Camera& camera, const DirectionalLight& light,
              const DrawOptions& options = {});

    /// The sky of `look` (Shading::Water's: its gradient, sun glow or environment image) behind
    /// everything in the bound framebuffer, for the view of `camera` and the sun of `light`:
    /// what the water reflects and fades into at the horizon. Writes no depth.
    void drawSky(const Camera& camera, const DirectionalLight& light, const WaterLook& look);

    /// Draws a mesh in one flat colour with its own depth (for scenes and tests); with a light,
    /// Lambert-lit (two-sided) and receiving the light's shadow map.
    void drawFlat(const Mesh& mesh, const glm::mat4& model, const Camera& camera,
                  const glm::vec4& color, const DirectionalLight* light = nullptr);

    /// Shadow casters, drawn into `map` between its begin() and end() (throws hfx::Error before
    /// its fit() or outside its pass): a surface writes the depth its technique traces along the
    /// light's rays (the relief, not the polygon; shaders/surface.frag, HFX_SHADOW_CASTER), a flat
    /// mesh its own.
    void drawShadow(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
                    const SurfaceMaterial& material, const ShadowMap& map, const DrawOptions& options = {});
    void drawShadow(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
                    const SurfaceMaterial& material, const ShadowMap& map, const DrawOptions& options = {});
    void drawFlatShadow(const Mesh& mesh, const glm::mat4& model, const ShadowMap& map);
    /// The same casters drawn into a shadow map of the engine's own (a cascade of its sun's, a
    /// spot light's, a tile of its shadow atlas): the caller binds its framebuffer, viewport, clip
    /// control and clear, and `lightView` is the light's view as a camera
    /// (Camera::fromMatrices(lightView, lightProjection[, reversedZ]): orthographic for a
    /// directional light, perspective for a spot light). A surface writes the depth its tracer
    /// finds along the light's rays, as into a ShadowMap, under the depth convention the camera
    /// says; no colour buffer is written (a colour attachment keeps what it holds). A draw throws
    /// hfx::Error where the clip control is not the camera's (checked as for a camera's draw).
    void drawShadow(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
                    const SurfaceMaterial& material, const Camera& lightView, const DrawOptions& options = {});
    void drawShadow(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
                    const SurfaceMaterial& material, const Camera& lightView, const DrawOptions& options = {});
    void drawFlatShadow(const Mesh& mesh, const glm::mat4& model, const Camera& lightView);

    /// How every draw's colours are encoded (ColorOutput; Auto by default). A flat mesh's unlit
    /// colour is written as given.
    void setColorOutput(ColorOutput output) { colorOutput_ = output; }
    ColorOutput colorOutput() const { return colorOutput_; }

    /// Where every camera's surface draw and the sky write each pixel's screen motion since the
    /// previous frame, for an engine's temporal anti-aliasing or motion blur: draw buffer
    /// `drawBuffer` (1 to 7) of the bound framebuffer (a two-channel float target, RG16F or RG32F,
    /// or a signed normalized one: a draw refuses an unsigned normalized or integer one by name,
    /// which could not hold a negative motion), as (x, y) in the viewport's uv units (1 across it),
    /// now less then, without the camera's jitter. A surface's pixel moves as its traced point does
    /// (the relief's, not the polygon's: Camera::previousViewProjection,
    /// DrawOptions::previousModel); the sky's as its direction; a point behind the previous frame's
    /// eye, 0. 0 (the default): none. Whatever is set, a draw writes no draw buffer but colour
    /// buffer 0, this one, the surface outputs (setSurfaceOutputs) and a trace output asked for: an
    /// engine's other targets keep what they hold. Throws hfx::Error for a buffer outside 0 to 7,
    /// or one the surface outputs name.
    void setMotionOutput(int drawBuffer);
    int motionOutput() const { return motionOutput_; }

    /// Where every camera's surface draw writes what a deferred engine's lighting reads of the
    /// traced point (SurfaceOutputs: its normal, albedo and shading channels, the relief's
    /// self-shadow among them), so that the engine's own lights shade the relief; buffer 0 still
    /// gets HFX's forward shading. Where the material is set, the exact tracer's light walks stay
    /// in the draw (DrawOptions::deferShadowWalks rewrites colours only). Throws hfx::Error for a
    /// buffer outside 0 to 7 or one named twice (the motion's among them).
    void setSurfaceOutputs(const SurfaceOutputs& outputs);
    const SurfaceOutputs& surfaceOutputs() const { return outputs_; }

    /// Builds a shader variant now (start-up) instead of on its first draw, and returns it.
    const ShaderProgram& program(const DrawOptions& options, const SurfaceVariant& variant = {});
    /// The exact tracer's unit: its last decision (TracerFrame: the texel shadows' stride, the
    /// pixels per texel it was made from) for reports.
    const ExactTracer& tracer() const { return tracer_; }
    ExactTracer& tracer() { return tracer_; } ///< its memory(), release()

private:
    /// Fills the transforms and binds the blocks' buffers (the guard restores them).
    void bindUniforms(SurfaceUniforms& u, const glm::mat4& model, const glm::mat4& viewProj);
    /// Who sees a surface draw: a camera, which gets a colour, or a light (a shadow caster's
    /// draw: depth only), whose view has everything it holds in front of its near plane (a
    /// ShadowMap's, fitted around them) or may not (an engine's own).
    enum class Viewer { Camera, LightAroundAll, Light };
    /// A surface draw: the uniforms of the layers and material, seen by `camera` (or, casting,
    /// the light's view), then the mesh.
    void drawSurface(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
                     const SurfaceMaterial& material, const Camera& camera, const DirectionalLight& light,
                     const DrawOptions& options, Viewer viewer);
    /// Binds the light's shadow maps (a ShadowMap's, an engine's cascades) for a draw that
    /// receives them, and returns the HFX_SHADOW_MAP variant (0: none).
    int receiveShadows(const DirectionalLight& light);
    /// camera: the eye the colour is shaded for (none for a shadow map, which gets no colour);
    /// reversedZ: the view's depth convention (Camera::reversedZ; a shadow map's is GL's default).
    void drawFlatSeenBy(const Mesh& mesh, const glm::mat4& model, const glm::mat4& viewProj, const Camera* camera,
                        bool reversedZ, const glm::vec4& color, const DirectionalLight* light);

    std::map<std::tuple<Technique, bool, SurfaceVariant>, ShaderProgram> programs_;
    ShaderProgram flat_[3]; ///< by the shadow maps received (SurfaceVariant::shadowMap)
    std::map<std::pair<SkyKind, int>, ShaderProgram> sky_; ///< by the sky's kind, the motion's draw buffer
    GlBuffer surfaceBlock_, waterBlock_, ringBlock_, planetBlock_, shadowBlock_;
    /// The comparison samplers the received shadow maps are read through, by the maps' depth
    /// convention ([1]: reversed), whatever the engine's textures' own state.
    GlSampler shadowSamplers_[2];
    RingShine ringShine_; ///< a planet's rings' light on it
    GlVertexArray empty_; ///< the sky's full-screen triangle has no vertex data
    ExactTracer tracer_; ///< the exact tracer's data and passes, and the bounded searches' bounds
    ColorOutput colorOutput_ = ColorOutput::Auto;
    int motionOutput_ = 0;
    SurfaceOutputs outputs_;
};

} // namespace hfx
