#version 450 core
// The rings' light on their planet (ring shine): per point of the cloud tops, the irradiance of
// the sunlight the rings scatter towards it, as a share of the sun's (per colour: the particles'
// albedo), which shade/planet.glsl adds to a point's light (hfx_ring_shine reads it). The renderer
// runs it where the profile, the rings' radii or the sun's elevation over their plane change.
//
// In a frame fixed to the sun: the planet a sphere of radius 1 at the origin, the rings in the
// plane y = 0 from u_inner to u_outer, the sun towards (cos b, sin b, 0). Texel (i, j) is the
// point at longitude pi (i + 1/2) / width from the sun's meridian and at latitude sin = -1 +
// 2 (j + 1/2) / height. Its light is the integral over the rings it sees (above its horizon:
// a point q of the rings shows where (q - p).n > 0, the sphere hiding the rest) of
//   E = 1/pi  sum  w(r) S(q) f(tau(r), mu, mu0) cos(theta_p) mu dA / d^2
// with d the distance to the ring element dA = r dr da, mu the cosine at the element between the
// rings' normal and the way to the point, cos(theta_p) the same at the point with its normal,
// f the single scattering towards the point (hfx_ring_scattered: the face the sun lights where
// the point is on the sun's side of the plane, else through the slab), w and tau the profile's
// albedo and optical depth there (its mip at the radial step), and S(q) 0 where the planet's
// shadow (a cylinder: the sun's disc is a few thousandths of a radius there) covers the element.
// The mid-point rule over u_radial x u_around elements.
layout(local_size_x = 8, local_size_y = 8) in;
#include "bindings.glsl"
#include "shade/rings.glsl"
layout(rgba16f, binding = HFX_IMAGE_RING_SHINE) writeonly uniform image2D i_shine;
uniform ivec2 u_size;      // the table's texels: longitude, latitude
uniform float u_inner;     // the rings' edges, planet radii
uniform float u_outer;
uniform vec2 u_sun;        // (cos b, sin b): the sun's elevation b over the rings' plane
uniform float u_profileLevel; // the profile's mip whose texel is one radial step
uniform int u_radial;      // elements across the rings
uniform int u_around;      // ... and around them

void main() {
    const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, u_size))) return;
    const float longitude = HFX_RING_PI * (float(texel.x) + 0.5) / float(u_size.x);
    const float sinLatitude = -1.0 + 2.0 * (float(texel.y) + 0.5) / float(u_size.y);
    const float cosLatitude = sqrt(max(1.0 - sinLatitude * sinLatitude, 0.0));
    const vec3 p = vec3(cosLatitude * cos(longitude), sinLatitude, cosLatitude * sin(longitude)); // = its normal
    const vec3 sun = vec3(u_sun, 0.0);
    const float mu0 = max(abs(u_sun.y), 1e-3);
    const bool litFace = p.y * u_sun.y > 0.0;
    const float dr = (u_outer - u_inner) / float(u_radial), da = 2.0 * HFX_RING_PI / float(u_around);
    const vec2 turn = vec2(cos(da), sin(da));
    vec3 light = vec3(0.0);
    for (int k = 0; k < u_radial; ++k) {
        const float r = u_inner + (float(k) + 0.5) * dr;
        const vec4 profile = textureLod(s_ringProfile, vec2((float(k) + 0.5) / float(u_radial), 0.5), u_profileLevel);
        const float tau = -log(max(1.0 - profile.a, 1e-6));
        float sum = 0.0;
        vec2 around = vec2(cos(0.5 * da), sin(0.5 * da)); // the element's (cos a, sin a), turned step by step
        for (int m = 0; m < u_around; ++m) {
            const vec3 q = vec3(r * around.x, 0.0, r * around.y);
            around = vec2(around.x * turn.x - around.y * turn.y, around.x * turn.y + around.y * turn.x);
            const vec3 d = q - p;
            const float d2 = dot(d, d), inverse = inversesqrt(d2);
            const float cosPoint = dot(p, d) * inverse;
            const float along = dot(q, sun);
            if (cosPoint <= 0.0 || (along < 0.0 && r * r - along * along < 1.0)) continue; // below the horizon, or in the shadow
            const float mu = abs(p.y) * inverse;
            sum += hfx_ring_scattered(tau, max(mu, 1e-4), mu0, litFace) * cosPoint * mu / d2;
        }
        light += profile.rgb * (sum * r);
    }
    imageStore(i_shine, texel, vec4(light * (dr * da / HFX_RING_PI), 1.0));
}
