#pragma once
// Picking on a displaced surface: a world-space ray (the camera's ray through the cursor) meets
// the height field that POM draws, found exactly by the bilinear ray/height-field intersection
// (HeightFieldTracer), so a click lands on the texel the user sees, not on the flat polygon: on
// a flat patch (pickSurface) or on any mesh as SurfaceRenderer draws it (pickMesh: curved, with
// a silhouette fade, or triplanar mapped, its parts in front of one another as the depth test
// keeps them, and given the pixel's neighbours at its level of detail; MeshPicker: the same
// through a hierarchy of boxes).
//
// pickSurface and pickMesh own nothing; a MeshPicker owns its copy of the mesh and its hierarchy.
// Thread: any; pure CPU work.

#include "hfx/core/Camera.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/Mesh.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace hfx {

struct SurfaceMaterial;

/// An affine patch of surface: the world position at texcoords (0, 0), dP/du, dP/dv and the unit
/// normal (the side the relief rises towards; h = 1 lies on the patch, h = 0 depthScale texture
/// units below it, as the shader traces).
struct SurfaceFrame {
    glm::dvec3 origin;
    glm::dvec3 tangent;
    glm::dvec3 bitangent;
    glm::dvec3 normal;
    /// The frame of a makePlane mesh drawn with `model`.
    static SurfaceFrame ofPlane(const PlaneConfig& plane, const glm::mat4& model = glm::mat4(1.0f));
};

struct SurfacePick {
    glm::dvec2 uv;     ///< texcoords of the hit (may lie outside [0,1) on a repeating plane)
    glm::dvec3 world;  ///< the displaced point in world space
    double height;     ///< h at the hit
};

/// The first point where `ray` meets the relief under `frame`, or nothing. `uvBounds`
/// (umin, vmin, umax, vmax) limits the patch: hits outside are misses. Throws hfx::Error naming
/// a ray or frame that is not finite, a ray of no direction, or a bad depthScale.
std::optional<SurfacePick> pickSurface(const Ray& ray, const SurfaceFrame& frame,
                                       const HeightFieldTracer& heights, double depthScale,
                                       glm::dvec4 uvBounds = {-1e30, -1e30, 1e30, 1e30});

/// What pickMesh found: the relief's point in the texture frame its pixel is traced in, the
/// triangle the ray entered (its corners are indices[3 triangle .. 3 triangle + 2]) and where.
struct MeshPick : SurfacePick {
    std::uint32_t triangle = 0;
    glm::dvec3 entry{0.0};  ///< where the ray met that triangle, world space
    glm::dvec3 normal{0.0}; ///< the mesh's unit normal there (its vertices', interpolated), world space
    /// The triplanar mapping's projection the uv belong to (0: along x, 1: y, 2: z; the
    /// heaviest at the entry, as the trace output's), or -1: the mesh's own texcoords.
    int projection = -1;
};

/// The rays through the pixels beside a picked one: one across and one up or down. Given them,
/// pickMesh has the draw's level of detail: the mip level of the texcoords' spread from the
/// pick's ray to theirs (what the draw's derivatives give), the relief faded out over the level
/// below SurfaceMaterial::lodThreshold (the point shown slides along the ray from the hit back to
/// the polygon) and flat past it.
struct PixelNeighbours {
    Ray across;
    Ray up;
    /// Pixel (x, y)'s in a width x height image of `camera` (y from the bottom, as
    /// Camera::rayThroughPixel and gl_FragCoord count it): the rays through the other pixels of
    /// its 2x2 quad across and up or down, the pairs a GPU's derivatives difference. (The pixels at
    /// x + 1 and y + 1 put the picks of Picking.GivenThePixelsNeighboursAPickFadesTheRelief...
    /// up to 0.47 texels from the drawn point, an eighth of a pixel or less in the fade; these,
    /// 0.0003.)
    static PixelNeighbours of(const Camera& camera, double x, double y, int width, int height);
};

/// The point of the relief SurfaceRenderer draws on `mesh` under `model` with `material` that
/// the ray's pixel shows, or nothing. Each triangle the ray enters from its front (counter-
/// clockwise as seen, turned with a mirroring model) is traced in the frame a pixel there is
/// traced in, and the nearest of their points along the ray is picked, as the draw's depth test
/// keeps it: a nearer part of the mesh passing in front of a deep hit shows (and is picked)
/// though the ray entered it later. That frame is the mesh's texcoords and tangent frame
/// interpolated at the entry point, or the heaviest projection of material.triplanar. The tracer
/// is exact (what hier draws; the sampled searches land within their step of it). The depth
/// scale is material.depthScale, faded by material.silhouetteFade as the view grazes the entry
/// normal, and 0 where the frame is degenerate (a sphere's poles): there the pick is the
/// polygon's point.
///
/// A triangle whose hit leaves material.patchBounds under clipToPatch offers no point, as its
/// pixel is discarded. A back face nearer than every point found (the mesh seen from behind or
/// inside) picks nothing, as a ray from below the relief does, unless the mesh is closed
/// (MeshData::closed) and a front face came first: the renderer culls it then (or, with the eye
/// near the mesh, its polygon lies behind that face's; a relief deeper than the solid is thick
/// there is the one place the draw can differ). The level of detail (lodThreshold) needs the
/// pixel's `neighbours`: without them the relief is picked at any distance. The heights are those
/// of the drawn surface, row 0 at v = 0 (DecalWallEffect::heightTracer, a SurfaceMaps' heights);
/// their size is the drawn surface's, what its mip levels count. O(triangles): 0.22 ms for
/// makeSphere's 9,216 on one thread of an Intel Xeon (Skylake-AVX512), and 1.4x pickSurface's
/// trace alone for a plane's 2 triangles (hfx-bench-kernels --benchmark_filter=BM_Pick); a
/// MeshPicker picks the same in 1.55 us on that sphere.
///
/// Throws hfx::Error naming the problem: a ray not finite or of no direction, a model matrix
/// not finite or without an inverse, a bad mesh (MeshData::validate) or material
/// (SurfaceMaterial::validate, less the shading model's look: no GL call), or neighbours whose
/// rays are not finite or have no direction.
std::optional<MeshPick> pickMesh(const Ray& ray, const MeshData& mesh, const glm::mat4& model,
                                 const HeightFieldTracer& heights, const SurfaceMaterial& material,
                                 const std::optional<PixelNeighbours>& neighbours = std::nullopt);

/// pickMesh on a mesh picked many times: a bounding volume hierarchy over its triangles (in
/// object space, built once, O(n log n)) passes over the triangles a ray cannot cross, and the
/// rest are crossed as pickMesh crosses them, so a pick is pickMesh's to the bit, under any
/// model matrix (MeshPicker.PicksWhatPickMeshPicksToTheBit). Owns a copy of the mesh.
/// Thread: any; const picks may run concurrently.
class MeshPicker {
public:
    /// Throws hfx::Error for a bad mesh (MeshData::validate).
    explicit MeshPicker(MeshData mesh);
    /// pickMesh(ray, mesh(), model, heights, material, neighbours); throws as it does (its
    /// messages begin "MeshPicker::pick").
    std::optional<MeshPick> pick(const Ray& ray, const glm::mat4& model, const HeightFieldTracer& heights,
                                 const SurfaceMaterial& material,
                                 const std::optional<PixelNeighbours>& neighbours = std::nullopt) const;
    const MeshData& mesh() const { return mesh_; }
    /// The hierarchy's nodes (a leaf holds at most 4 triangles).
    size_t nodeCount() const { return nodes_.size(); }

private:
    struct Node {
        glm::dvec3 lo{0.0}, hi{0.0};
        std::uint32_t first = 0, count = 0; ///< a leaf's triangles in order_, or (count 0) its first child
    };
    MeshData mesh_;
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> order_;
};

} // namespace hfx
