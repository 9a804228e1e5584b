// What a shading model (shade/*.glsl) is given: the traced point, lit by the directional light.
// Each model defines vec3 hfx_shade(HfxSurfacePoint p), the linear colour of the pixel; the sky
// (shade/sky.glsl) is composed before every model.

struct HfxSurfacePoint {
    vec3 albedo;          // the colour map at the hit
    vec3 normal;          // world space, unit: the relief's normal at the hit
    vec3 geometricNormal; // world space, unit: the mesh's own
    vec3 position;        // world space: the displaced point
    vec2 texcoord;        // the hit's texcoords (the mesh's: layer 0's texture space)
    float footprint;      // the texcoords a pixel spans there (the hits' spread to the next pixel)
    vec3 viewDir;         // world space, unit, towards the eye
    vec3 lightDir;        // world space, unit, towards the light
    float height;         // h at the hit (1 = the polygon)
    float lit;            // 1 - self-shadow, faded in from the geometric terminator
    float cosView;        // between the geometric normal and the view
    float diffuse;        // max(N.L, 0)
    float specular;       // Blinn-Phong lobe (u_specularPower, widened by slopeVariance and roughness), 0 facing away
    float roughness;      // added to the material's: the shading channels' R (0 where none were given)
    float occlusion;      // ambient occlusion, 1 open: the shading channels' G
    float glow;           // heat, 0 none to 1: the shading channels' A (a fresh crater's embers)
    float slopeVariance;  // variance of the slopes the pixel covers, from the mip-averaged normals (Toksvig)
    vec4 foam;            // each layer's albedo alpha: foam coverage, where the effect writes it (layers 0-3)
    vec4 foamYoung;       // each layer's albedo red: the young part of that foam (the ocean's)
    vec4 foamDetail;      // for each layer, the next finer layer's height in [0,1]: thin foam survives on its crests
};
