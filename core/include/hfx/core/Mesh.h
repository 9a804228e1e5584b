#pragma once
// Triangle meshes carrying the tangent frame POM needs. The tangent and bitangent are the
// derivatives of position with respect to the texcoords (world units per texcoord unit), not unit
// vectors: with them the shader converts the view ray into texture space exactly, whatever the
// mesh's size and texture repeat.
//
// MeshData is a value; Mesh owns its GL buffers and vertex array. Thread: Mesh on the thread
// whose GL context is current; makePlane/makeSphere anywhere.

#include "hfx/core/GlObject.h"
#include "hfx/core/Uid.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace hfx {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;    ///< unit geometric normal
    glm::vec3 tangent;   ///< dP/du
    glm::vec3 bitangent; ///< dP/dv
    glm::vec2 texcoord;
};

struct MeshData {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices; ///< triangles, counter-clockwise seen from the normal side
    /// The triangles bound a convex solid (or lie in one plane), counter-clockwise seen from
    /// outside: seen from anywhere, no two front faces overlap on the screen. makePlane's and
    /// makeSphere's are (isConvex checks it). What the exact tracer's walks in a compute pass need
    /// (TracePass::Compute: one fragment per pixel). False by default: say so for your own mesh
    /// (Mesh checks the claim at its edges: checkMeshClaims).
    bool convex = false;
    /// The triangles enclose a solid, counter-clockwise seen from outside: from a point outside
    /// it, every back face lies behind a front face. makeSphere's do. The renderer then culls the
    /// back faces where the eye is outside the mesh's bounds (SurfaceRenderer: a back face drawn
    /// before the front face over it is shaded, and on llvmpipe, where a program that writes its
    /// depth has no early depth test, every one is). Checked by Mesh like `convex`.
    bool closed = false;

    /// Throws hfx::Error naming the first fault: no triangles, an index count not a multiple of
    /// 3, an index past the vertices, or a vertex whose position, normal, tangent, bitangent or
    /// texcoord is not finite, or whose normal has no direction. A zero tangent or bitangent is
    /// allowed: there the texture frame is degenerate (a sphere's pole) and every technique
    /// normal maps. Mesh's constructor calls it (through checkMeshClaims).
    void validate() const;
};

struct PlaneConfig {
    float size = 2.0f;          ///< edge length in world units, centred on the origin
    float texcoordScale = 1.0f; ///< texcoords run 0..texcoordScale across the plane
    int subdivisions = 1;       ///< quads per edge
    void validate() const;
};

/// A square in the XZ plane, normal +Y; u grows along +X and v along -Z, so T x B = N.
MeshData makePlane(const PlaneConfig& config = {});

struct SphereConfig {
    float radius = 1.0f;
    int segments = 96; ///< quads around the equator (u)
    int rings = 48;    ///< quads from pole to pole (v)
    void validate() const;
};

/// A longitude-latitude sphere centred on the origin: u = longitude / 2 pi (the seam's
/// vertices are doubled, u = 0 and 1), v = 0 at the south pole and 1 at the north (+Y).
/// T = dP/du, B = dP/dv exactly, so T x B points outwards; at the poles T vanishes.
MeshData makeSphere(const SphereConfig& config = {});

struct CylinderConfig {
    float radius = 0.5f;
    float height = 2.0f;                   ///< along +Y, centred on the origin
    int segments = 64;                     ///< quads around (u)
    glm::vec2 texcoordScale{1.0f, 1.0f};   ///< texcoords run 0..x around and 0..y from bottom to top
    void validate() const;
};

/// The side of a cylinder about the Y axis (a pillar, a pipe; open, no caps): u grows around it
/// as a longitude would on makeSphere (the seam's vertices doubled), v from bottom to top. T =
/// dP/du, B = dP/dv exactly, so T x B points outwards. Convex (its faces are a prism's sides),
/// not closed.
MeshData makeCylinder(const CylinderConfig& config = {});

/// True where every vertex lies on or behind the plane of every triangle (within 1e-5 of the
/// mesh's extent) and the triangles face outwards (the normal side): what MeshData::convex
/// declares. O(triangles x vertices): a check for tests, not for every mesh made.
bool isConvex(const MeshData& data);

/// What MeshData::closed and convex claim, checked at the edges (vertices within 1e-6 of the
/// mesh's extent are one point: a sphere's seam and poles): a closed mesh has two faces on every
/// edge, running along it in opposite directions; a convex one has each face's far corner on or
/// behind the plane of the face beside it; and unless it is closed and in one part (then convex
/// at every edge is convex), either all its faces lie in one plane or every vertex lies on or
/// behind every face (two spheres side by side, a sheet rolled past a turn: each convex at every
/// edge), checked whole, O(triangles x vertices), up to 2e8 pairs (past that, faces in parts that
/// share no edge are refused by name, and an open mesh in one part is checked at its edges only).
/// Throws hfx::Error naming the claim and the edge or point (or MeshData::validate's fault: it
/// calls that first); the Mesh constructor calls it. O(triangles log triangles) for a closed mesh
/// in one part or a flat one: 3.5 ms for makeSphere's default, 0.7 s for a million triangles (on
/// the 2-core development machine).
void checkMeshClaims(const MeshData& data);

/// True where the mesh is one flat patch with one texture frame: every vertex has the first's
/// normal, tangent and bitangent, and lies where its texcoords put it in that frame (position =
/// p0 + T (u - u0) + B (v - v0), within 1e-5 of the mesh's extent). makePlane's are; a sphere's
/// are not. What the exact tracer's beam start needs (SurfaceRenderer): the rays of a block of
/// pixels then meet one plane in one frame.
bool isFlatPatch(const MeshData& data);

/// A flat patch's texture frame and outline in the mesh's own space: the position at texcoords
/// (0, 0), dP/du, dP/dv and the unit normal, the corners of its texcoords' bounding box in order
/// (for makePlane, its four corners) and that box. What the exact tracer derives a flat surface's
/// light, its area on the screen and its pixels' rays from (ExactTracer).
struct FlatPatch {
    glm::vec3 origin;
    glm::vec3 tangent;
    glm::vec3 bitangent;
    glm::vec3 normal;
    std::array<glm::vec3, 4> corners;
    glm::vec2 texcoordMin, texcoordMax;
};

/// The patch of a mesh isFlatPatch accepts; empty for any other.
std::optional<FlatPatch> flatPatchOf(const MeshData& data);

/// Vertex and index buffers plus a vertex array, laid out as Vertex (locations 0..4).
class Mesh {
public:
    Mesh() = default;
    explicit Mesh(const MeshData& data);
    void draw() const;
    GLsizei indexCount() const { return indexCount_; }
    bool flatPatch() const { return patch_.has_value(); } ///< isFlatPatch of its data
    bool convex() const { return convex_; }                ///< its data's MeshData::convex, or a flat patch
    bool closed() const { return closed_; }                ///< its data's MeshData::closed
    /// A sphere around every vertex: its centre (xyz) and radius (w), in the mesh's space.
    glm::vec4 bounds() const { return bounds_; }
    const std::optional<FlatPatch>& patch() const { return patch_; } ///< flatPatchOf its data
    /// Unique to this mesh in this process (never reused; a move takes it along): what the exact
    /// tracer keeps its choices for a mesh by (ExactTracer::passTrial).
    std::uint64_t uid() const { return uid_.value(); }

private:
    GlBuffer vertices_, indices_;
    GlVertexArray vao_;
    GLsizei indexCount_ = 0;
    std::optional<FlatPatch> patch_;
    bool convex_ = false, closed_ = false;
    glm::vec4 bounds_{0.0f};
    Uid uid_;
};

} // namespace hfx
