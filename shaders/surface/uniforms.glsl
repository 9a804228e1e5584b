// The uniforms of a surface draw, set once per draw as one std140 block. Mirrored field for
// field by hfx::SurfaceUniforms (effects/src/SurfaceUniforms.h); a test compares the offsets the
// driver reports with the C++ struct's. Included by both stages of the surface program.

layout(std140, binding = HFX_BLOCK_SURFACE) uniform HfxSurface {
    mat4 u_model;
    mat4 u_viewProj;
    mat4 u_normalMatrix;      // inverse transpose of u_model's 3x3, in the upper left
    vec4 u_patchBounds;       // umin, vmin, umax, vmax
    vec3 u_cameraPos;
    float u_depthScale;       // texture units between h = 1 and h = 0
    vec3 u_lightDir;          // world space, towards the light, unit length
    float u_normalScale;      // u_depthScale / the depth the stored normals were made for
    vec3 u_lightColor;
    float u_lodThreshold;     // mip level from which on only normal mapping is done
    vec3 u_ambient;
    float u_shadowSharpness;  // how fast a blocker's occlusion saturates
    vec2 u_normalDecode;      // stored normal * x + y: (1, 0) for float formats, (2, -1) for unorm8
    float u_specularStrength;
    float u_specularPower;
    float u_silhouetteFade;   // curved meshes: relief fades where cos(view) drops below this
    int u_minSamples;         // linear-search steps looking straight down
    int u_maxSamples;         // ... and at grazing angles
    int u_shadowSamples;
    int u_clipToPatch;        // 1: discard rays that leave u_patchBounds (finite patches)
    float u_varianceFloor;    // slope variance the storage format's rounding alone shows (not roughness)
    ivec2 u_fieldLast;        // the field's last texel: its size - 1
    ivec2 u_wrapMask;         // per axis: u_fieldLast where the edges wrap, -1 where they clamp
    float u_untracedHeight;   // the untraced layers' share of the height: sum weight * rest height
    float u_pixelBudget;      // the screen error the exact tracer may leave, pixels (0: exact)
    // Layered surfaces (HFX_LAYERS > 1, the ocean's cascades), one component per layer:
    vec4 u_layerScale;        // layer texcoords = the mesh's texcoords * scale
    vec4 u_layerWeight;       // its share of the height: h = sum weight * h_layer
    vec4 u_layerSlope;        // depthScale * weight * scale / the layer's normal depth: its slopes' share
    vec4 u_layerLevel;        // its mip level minus layer 0's read unscaled: log2(scale * size / size0)
    int u_linearOutput;       // 1: colours written linear, unclamped (hfx::ColorOutput); 0: gamma 2.2
    // The texel shadows' light (hfx::ShadowLight; read where HFX_TEXEL_SHADOWS is 1): texcoords
    // per unit climbed, penumbra, slack
    vec4 u_shadowLight;
    vec2 u_texelSize;         // 1 / the field's size: a level-0 cell's gather coordinate in one fma
    // The exact tracer's walks in a compute pass (HFX_COMPUTE_TRACE, trace/hier/trace.glsl):
    int u_traceWidth;         // the viewport's width: a pixel's slot is (y - y0) * width + x - x0
    uint u_traceStamp;        // this draw's mark on the slots its pixels wrote
    ivec2 u_traceOrigin;      // the viewport's origin, x0 and y0
    int u_traceHeight;        // the viewport's height
    int u_reversedZ;          // 1: the view's depth is reversed (near at 1, [0, 1] clip depth)
    // The screen motion (hfx::SurfaceRenderer::setMotionOutput, HFX_MOTION_OUTPUT):
    mat4 u_previousFromWorld; // this frame's world to the previous frame's clip space
    vec2 u_jitter;            // the jitter u_viewProj holds (NDC), left out of the motion
    // A triplanar mapping (hfx::TriplanarMapping, HFX_TRIPLANAR):
    float u_triplanarScale;     // texcoords per unit of the mesh's own space
    float u_triplanarSharpness; // the blend weights' power
    vec3 u_towardsEye;        // an orthographic camera's direction towards the eye (u_orthographic)
    int u_orthographic;       // 1: every view ray runs along -u_towardsEye; 0: from u_cameraPos
};

// Towards the eye from the point p (not unit length): to the camera's position, or an
// orthographic camera's one direction (hfx::Camera::orthographic: parallel rays).
vec3 hfx_to_eye(vec3 p) {
    return u_orthographic != 0 ? u_towardsEye : u_cameraPos - p;
}

// The colour a pass writes, from linear radiance (hfx::ColorOutput): clamped to [0, 1] and encoded
// with gamma 2.2 for a plain 8-bit target; linear and unclamped (up to a half float's largest)
// for a float target, or an sRGB one that encodes it itself.
vec3 hfx_output(vec3 linearColor) {
    return u_linearOutput != 0 ? clamp(linearColor, 0.0, 65504.0) : pow(clamp(linearColor, 0.0, 1.0), vec3(1.0 / 2.2));
}

// Rings of waves from impacts on the water (HFX_RINGS: the water shading), in the mesh's
// texcoords; mirrored by hfx::RingUniforms. They are not tiled with the layers.
#define HFX_MAX_RINGS 8
layout(std140, binding = HFX_BLOCK_RINGS) uniform HfxRings {
    vec4 u_ringShape[HFX_MAX_RINGS]; // centre u, v, radius, width
    vec4 u_ringWave[HFX_MAX_RINGS];  // wavenumber (radians per texcoord), amplitude (h units), foam, 0
    int u_ringCount;
};

// A direction along a pixel's ray, from two of its points unprojected, turned away from the eye
// where they came out of order: through an oblique near plane (a planar reflection's clip at the
// water) the far plane tilts, lies behind the eye for some rays (past infinity), and the far
// point less the near one then points back. u_viewProj's clip w grows away from the eye (an
// orthographic view's is constant, and its points come in order).
vec3 hfx_away_from_eye(vec3 along) {
    return dot(vec3(u_viewProj[0][3], u_viewProj[1][3], u_viewProj[2][3]), along) < 0.0 ? -along : along;
}

// A point's screen motion since the previous frame (hfx::SurfaceRenderer::setMotionOutput), in the
// viewport's uv units (1 across it), now less then, without the jitter; `world` a point (w = 1)
// or, for the sky, a direction (w = 0). A point at or behind the previous frame's eye was nowhere
// on its screen: 0, not an infinity or a NaN in the engine's history.
vec2 hfx_motion(vec4 world) {
    const vec4 now = u_viewProj * world, then = u_previousFromWorld * world;
    return then.w > 0.0 ? 0.5 * ((now.xy / now.w - u_jitter) - then.xy / then.w) : vec2(0.0);
}
