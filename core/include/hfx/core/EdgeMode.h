#pragma once
// How a field continues beyond its edges, one name for every layer: the source says it
// (HeightSource::edges()), and the Sobel filter, the height pyramid, the decal stamps, the gas's
// boundaries, the GL textures' wrap modes, the tracers and the CPU intersection all follow it.
// Kernels get it as -D options from hfx::edgeOptions (compute/ClContext.h); shared math reads
// indices through hfx_edge_index (compute/shared/EdgeMath.h).
//
// Thread: any (plain values).

#include <glm/vec2.hpp>

namespace hfx {

/// Wrap tiles both ways; WrapU tiles u and clamps v (a longitude-latitude map, which wraps at the
/// date line but not over the poles); Clamp clamps both.
enum class EdgeMode { Wrap, Clamp, WrapU };

inline constexpr EdgeMode kEdgeModes[] = {EdgeMode::Wrap, EdgeMode::Clamp, EdgeMode::WrapU};

constexpr bool wrapsU(EdgeMode edges) { return edges != EdgeMode::Clamp; }
constexpr bool wrapsV(EdgeMode edges) { return edges == EdgeMode::Wrap; }
/// Per axis 1 where the field wraps, 0 where it clamps: the pyramid build's u_wrap (bounds.comp).
constexpr glm::ivec2 wrapFlags(EdgeMode edges) { return {wrapsU(edges) ? 1 : 0, wrapsV(edges) ? 1 : 0}; }
/// "wrap", "clamp", "wrap-u".
const char* edgeModeName(EdgeMode edges);

} // namespace hfx
