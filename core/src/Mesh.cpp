#include "hfx/core/Mesh.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hfx {

void PlaneConfig::validate() const {
    if (!(size > 0.0f) || !std::isfinite(size))
        throw Error(str("PlaneConfig.size must be positive and finite, got ", size));
    if (!(texcoordScale > 0.0f) || !std::isfinite(texcoordScale))
        throw Error(str("PlaneConfig.texcoordScale must be positive, got ", texcoordScale));
    if (subdivisions < 1 || subdivisions > 4096)
        throw Error(str("PlaneConfig.subdivisions must be in [1, 4096], got ", subdivisions));
}

MeshData makePlane(const PlaneConfig& config) {
    config.validate();
    MeshData mesh;
    const int n = config.subdivisions;
    const float dPdu = config.size / config.texcoordScale;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float s = float(i) / n, t = float(j) / n;
            Vertex v;
            v.position = {(s - 0.5f) * config.size, 0.0f, (0.5f - t) * config.size};
            v.normal = {0, 1, 0};
            v.tangent = {dPdu, 0, 0};
            v.bitangent = {0, 0, -dPdu};
            v.texcoord = {s * config.texcoordScale, t * config.texcoordScale};
            mesh.vertices.push_back(v);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
        }
    mesh.convex = true; // one plane
    return mesh;
}

void SphereConfig::validate() const {
    if (!(radius > 0.0f) || !std::isfinite(radius))
        throw Error(str("SphereConfig.radius must be positive, got ", radius));
    if (segments < 3 || segments > 4096 || rings < 2 || rings > 4096)
        throw Error(str("SphereConfig needs 3..4096 segments and 2..4096 rings, got ", segments,
                        " and ", rings));
}

void CylinderConfig::validate() const {
    if (!(radius > 0.0f) || !std::isfinite(radius) || !(height > 0.0f) || !std::isfinite(height))
        throw Error(str("CylinderConfig.radius and height must be positive, got ", radius, " and ", height));
    if (segments < 3 || segments > 4096) throw Error(str("CylinderConfig needs 3..4096 segments, got ", segments));
    if (!(texcoordScale.x > 0.0f) || !(texcoordScale.y > 0.0f) || !std::isfinite(texcoordScale.x) ||
        !std::isfinite(texcoordScale.y))
        throw Error(str("CylinderConfig.texcoordScale must be positive, got ", texcoordScale.x, ", ", texcoordScale.y));
}

void MeshData::validate() const {
    if (vertices.empty() || indices.empty() || indices.size() % 3 != 0)
        throw Error(str("mesh needs triangles, got ", vertices.size(), " vertices and ", indices.size(), " indices"));
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= vertices.size())
            throw Error(str("mesh index ", indices[i], " (entry ", i, ") is out of range (", vertices.size(),
                            " vertices)"));
    for (size_t i = 0; i < vertices.size(); ++i) {
        const Vertex& v = vertices[i];
        const auto check = [&](const char* name, auto value) {
            if (!isFinite(value))
                throw Error(str("mesh vertex ", i, ": its ", name, " ", text(value), " is not finite"));
        };
        check("position", v.position);
        check("normal", v.normal);
        check("tangent", v.tangent);
        check("bitangent", v.bitangent);
        check("texcoord", v.texcoord);
        // (The shader normalises the interpolated normal: a zero one there is a NaN.)
        if (!(glm::length(glm::dvec3(v.normal)) > 1e-6))
            throw Error(str("mesh vertex ", i, ": its normal ", text(v.normal), " has no direction (a unit normal is needed)"));
    }
}

MeshData makeSphere(const SphereConfig& config) {
    config.validate();
    MeshData mesh;
    const double pi = 3.14159265358979323846;
    const double r = config.radius;
    for (int j = 0; j <= config.rings; ++j)
        for (int i = 0; i <= config.segments; ++i) {
            const double u = double(i) / config.segments, v = double(j) / config.rings;
            const double lon = 2.0 * pi * u, lat = pi * (v - 0.5);
            const double cl = std::cos(lat), sl = std::sin(lat), co = std::cos(lon), so = std::sin(lon);
            Vertex vertex;
            vertex.normal = glm::vec3(glm::dvec3(cl * co, sl, -cl * so));
            vertex.position = vertex.normal * config.radius;
            vertex.tangent = glm::vec3(glm::dvec3(-cl * so, 0.0, -cl * co) * (2.0 * pi * r));
            vertex.bitangent = glm::vec3(glm::dvec3(-sl * co, cl, sl * so) * (pi * r));
            vertex.texcoord = {float(u), float(v)};
            mesh.vertices.push_back(vertex);
        }
    const int row = config.segments + 1;
    for (int j = 0; j < config.rings; ++j)
        for (int i = 0; i < config.segments; ++i) {
            const uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
        }
    // Each quad's corners lie on two parallels and two meridians: a plane's, and the sphere's
    // points are on the outer side of none (the pole's triangles are degenerate, of no area).
    mesh.convex = true;
    mesh.closed = true;
    return mesh;
}

MeshData makeCylinder(const CylinderConfig& config) {
    config.validate();
    MeshData mesh;
    const double pi = 3.14159265358979323846;
    const double r = config.radius, h = config.height;
    for (int j = 0; j <= 1; ++j)
        for (int i = 0; i <= config.segments; ++i) {
            const double u = double(i) / config.segments, lon = 2.0 * pi * u;
            const double co = std::cos(lon), so = std::sin(lon);
            Vertex vertex;
            vertex.normal = glm::vec3(glm::dvec3(co, 0.0, -so));
            vertex.position = glm::vec3(glm::dvec3(r * co, (j - 0.5) * h, -r * so));
            vertex.tangent = glm::vec3(glm::dvec3(-so, 0.0, -co) * (2.0 * pi * r / config.texcoordScale.x));
            vertex.bitangent = glm::vec3(0.0, h / config.texcoordScale.y, 0.0);
            vertex.texcoord = {float(u * config.texcoordScale.x), float(j * config.texcoordScale.y)};
            mesh.vertices.push_back(vertex);
        }
    const int row = config.segments + 1;
    for (int i = 0; i < config.segments; ++i) {
        const uint32_t a = uint32_t(i), b = a + 1, c = a + row, d = c + 1;
        mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
    mesh.convex = true;
    return mesh;
}

namespace {

/// The box around a mesh's vertices (it has some): its lowest and highest corners.
std::pair<glm::dvec3, glm::dvec3> positionBox(const MeshData& data) {
    glm::dvec3 lo(data.vertices.front().position), hi = lo;
    for (const Vertex& v : data.vertices) {
        lo = glm::min(lo, glm::dvec3(v.position));
        hi = glm::max(hi, glm::dvec3(v.position));
    }
    return {lo, hi};
}

/// Triangle `t`'s first corner and unit normal (its winding's), or none where it is degenerate (a
/// sphere's pole: no plane, no front, no edges of its own).
std::optional<std::pair<glm::dvec3, glm::dvec3>> facePlane(const MeshData& data, size_t t) {
    const glm::dvec3 a(data.vertices[data.indices[3 * t]].position), b(data.vertices[data.indices[3 * t + 1]].position),
        c(data.vertices[data.indices[3 * t + 2]].position);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double area = glm::length(n);
    const double longest = std::max({glm::dot(b - a, b - a), glm::dot(c - a, c - a), glm::dot(c - b, c - b)});
    if (!(area > 1e-6 * longest)) return std::nullopt;
    return std::pair{a, n / area};
}

} // namespace

bool isConvex(const MeshData& data) {
    if (data.vertices.empty() || data.indices.size() < 3) return false;
    const auto [lo, hi] = positionBox(data);
    const double tolerance = 1e-5 * std::max(glm::length(hi - lo), 1e-12);
    for (size_t t = 0; t < data.indices.size() / 3; ++t) {
        const auto plane = facePlane(data, t);
        if (!plane) continue;
        const auto& [a, unit] = *plane;
        // It faces where its vertices' normals point, and nothing lies in front of its plane.
        if (glm::dot(unit, glm::dvec3(data.vertices[data.indices[3 * t]].normal)) < 0.0) return false;
        for (const Vertex& v : data.vertices)
            if (glm::dot(unit, glm::dvec3(v.position) - a) > tolerance) return false;
    }
    return true;
}

namespace {

/// Vertices by position: those within `tolerance` of each other (a sphere's seam and poles, whose
/// vertices are doubled) get one id. Cells 64 tolerances wide: a point's own, and the neighbours'
/// where it lies within the tolerance of their side.
std::vector<uint32_t> pointIds(const MeshData& data, double tolerance, std::vector<glm::dvec3>& points) {
    struct Key {
        std::int64_t x, y, z;
        bool operator==(const Key&) const = default;
    };
    struct Hash {
        size_t operator()(const Key& k) const {
            return size_t(k.x * 73856093) ^ size_t(k.y * 19349663) ^ size_t(k.z * 83492791);
        }
    };
    // A cell's first point, and each point's next in its cell (none: UINT32_MAX).
    std::unordered_map<Key, uint32_t, Hash> cells;
    cells.reserve(data.vertices.size());
    std::vector<uint32_t> next, ids(data.vertices.size());
    for (size_t v = 0; v < data.vertices.size(); ++v) {
        const glm::dvec3 p(data.vertices[v].position);
        const double cell = 64.0 * tolerance;
        const glm::dvec3 q = glm::floor(p / cell), inside = p - q * cell;
        const Key key{std::int64_t(q.x), std::int64_t(q.y), std::int64_t(q.z)};
        const glm::ivec3 from(glm::lessThan(inside, glm::dvec3(tolerance))),
            to(glm::greaterThan(inside, glm::dvec3(cell - tolerance)));
        std::optional<uint32_t> found;
        for (int dz = -from.z; dz <= to.z && !found; ++dz)
            for (int dy = -from.y; dy <= to.y && !found; ++dy)
                for (int dx = -from.x; dx <= to.x && !found; ++dx)
                    if (auto it = cells.find({key.x + dx, key.y + dy, key.z + dz}); it != cells.end())
                        for (uint32_t id = it->second; id != UINT32_MAX && !found; id = next[id])
                            if (glm::length(points[id] - p) <= tolerance) found = id;
        if (!found) {
            found = uint32_t(points.size());
            points.push_back(p);
            auto [it, fresh] = cells.try_emplace(key, *found);
            next.push_back(fresh ? UINT32_MAX : it->second);
            it->second = *found;
        }
        ids[v] = *found;
    }
    return ids;
}

/// A convex claim where the edges cannot settle it: faces convex at every edge may still be two
/// convex solids side by side (parts that share no edge), or an open sheet that wraps past one
/// (a scroll rolled one and a half turns); either way front faces overlap on the screen. A closed
/// mesh in one part is convex (its edges said so); else either every face lies in one plane (a
/// patch, whole or in pieces: nothing overlaps), or every vertex must lie on or behind every
/// face's plane, checked whole: O(faces x vertices), up to kConvexWholeChecked pairs. Past that
/// a claim on parts is refused by name rather than checked for minutes, and an open mesh in one
/// part is taken on its edges' word.
constexpr double kConvexWholeChecked = 2e8;

template <typename Side>
void checkConvexWhole(const MeshData& data, const std::vector<Side>& sides,
                      const std::vector<glm::dvec3>& normals, double tolerance) {
    std::vector<uint32_t> parent(normals.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto root = [&](uint32_t t) {
        while (parent[t] != t) t = parent[t] = parent[parent[t]];
        return t;
    };
    for (size_t i = 1; i < sides.size(); ++i)
        if (sides[i].edge == sides[i - 1].edge)
            parent[root(sides[i].triangle)] = root(sides[i - 1].triangle);
    // The faces with a plane (degenerate ones have no sides) and their parts.
    std::vector<char> planar(normals.size(), 0);
    for (const Side& side : sides) planar[side.triangle] = 1;
    std::vector<uint32_t> faces;
    for (uint32_t t = 0; t < normals.size(); ++t)
        if (planar[t]) faces.push_back(t);
    if (faces.empty()) return;
    size_t parts = 0;
    for (const uint32_t t : faces) parts += root(t) == t;
    if (parts < 2 && data.closed) return;
    const auto corner = [&](uint32_t t) {
        return glm::dvec3(data.vertices[data.indices[3 * size_t(t)]].position);
    };
    const glm::dvec3 n0 = normals[faces[0]], a0 = corner(faces[0]);
    const auto inPlane = [&](uint32_t t) { return glm::length(normals[t] - n0) <= 1e-6; };
    const auto onPlane = [&](const Vertex& v) {
        return std::abs(glm::dot(n0, glm::dvec3(v.position) - a0)) <= tolerance;
    };
    const bool onePlane = std::ranges::all_of(faces, inPlane) && std::ranges::all_of(data.vertices, onPlane);
    if (onePlane) return;
    if (double(faces.size()) * double(data.vertices.size()) > kConvexWholeChecked) {
        if (parts < 2) return;
        throw Error(str("MeshData::convex, but its faces form ", parts,
                        " parts that share no edge, and its ", faces.size(), " faces and ",
                        data.vertices.size(), " vertices are too many to check that they lie on ",
                        "one convex solid: join the parts, or draw each as its own mesh"));
    }
    for (const uint32_t t : faces)
        for (const Vertex& v : data.vertices)
            if (glm::dot(normals[t], glm::dvec3(v.position) - corner(t)) > tolerance) {
                const std::string where = str("the point ", text(glm::dvec3(v.position)),
                                              " lies in front of the face at ", text(corner(t)));
                throw Error(parts > 1 ? str("MeshData::convex, but its faces form ", parts,
                                            " parts that share no edge, and ", where,
                                            ": they are not one convex solid (draw each as its "
                                            "own mesh)")
                                      : str("MeshData::convex, but ", where,
                                            ": the open mesh, convex at every edge, wraps past "
                                            "one convex solid"));
            }
}

} // namespace

void checkMeshClaims(const MeshData& data) {
    data.validate();
    if (!data.closed && !data.convex) return;
    const auto [lo, hi] = positionBox(data);
    const double extent = std::max(glm::length(hi - lo), 1e-30), tolerance = 1e-6 * extent;
    std::vector<glm::dvec3> points;
    const std::vector<uint32_t> id = pointIds(data, tolerance, points);
    // Each face's side of each edge: the edge's points (lower id first), the face, its corner off
    // the edge (a vertex index), and whether the face runs along the edge from the lower id.
    struct Side {
        std::uint64_t edge;
        std::uint32_t triangle, far;
        bool forward;
    };
    std::vector<Side> sides;
    sides.reserve(data.indices.size());
    std::vector<glm::dvec3> normals(data.indices.size() / 3);
    for (size_t t = 0; t < normals.size(); ++t) {
        const auto plane = facePlane(data, t);
        if (!plane) continue;
        normals[t] = plane->second;
        const std::array<uint32_t, 3> c = {data.indices[3 * t], data.indices[3 * t + 1], data.indices[3 * t + 2]};
        for (int e = 0; e < 3; ++e) {
            const std::uint64_t p = id[c[size_t(e)]], q = id[c[size_t((e + 1) % 3)]];
            sides.push_back({std::min(p, q) << 32 | std::max(p, q), std::uint32_t(t), c[size_t((e + 2) % 3)], p < q});
        }
    }
    std::ranges::sort(sides, {}, &Side::edge);
    for (size_t i = 0; i < sides.size();) {
        size_t j = i;
        while (j < sides.size() && sides[j].edge == sides[i].edge) ++j;
        const std::span<const Side> on(sides.data() + i, j - i);
        const auto where = [&] {
            const glm::dvec3 a = points[on[0].edge >> 32], b = points[on[0].edge & 0xffffffffu];
            return str("the edge from ", text(a), " to ", text(b));
        };
        if (data.closed && (on.size() != 2 || on[0].forward == on[1].forward))
            throw Error(str("MeshData::closed, but ", where(), " has ", on.size(),
                            on.size() == 2   ? " faces wound the same way"
                            : on.size() == 1 ? " face, not 2 (a hole)"
                                             : " faces, not 2"));
        if (data.convex && on.size() == 2)
            for (int k = 0; k < 2; ++k) {
                const Side& mine = on[size_t(k)];
                const Side& other = on[size_t(1 - k)];
                const glm::dvec3 corner(data.vertices[data.indices[3 * size_t(mine.triangle)]].position);
                if (glm::dot(normals[mine.triangle], glm::dvec3(data.vertices[other.far].position) - corner) > tolerance)
                    throw Error(str("MeshData::convex, but at ", where(), " the faces fold outwards (a dent or a ridge)"));
            }
        i = j;
    }
    // (Across parts, the tolerance of isConvex: a thin face's plane, carried far, tilts more.)
    if (data.convex) checkConvexWhole(data, sides, normals, 10.0 * tolerance);
}

bool isFlatPatch(const MeshData& data) {
    if (data.vertices.empty()) return false;
    const Vertex& first = data.vertices.front();
    double extent = 0.0;
    for (const Vertex& v : data.vertices)
        extent = std::max(extent, double(glm::length(v.position - first.position)));
    const double tolerance = 1e-5 * std::max(extent, 1e-6);
    const auto same = [&](glm::vec3 a, glm::vec3 b) {
        return double(glm::length(a - b)) <= 1e-5 * std::max(double(glm::length(b)), 1e-6);
    };
    for (const Vertex& v : data.vertices) {
        if (!same(v.normal, first.normal) || !same(v.tangent, first.tangent) || !same(v.bitangent, first.bitangent))
            return false;
        const glm::dvec2 d = glm::dvec2(v.texcoord) - glm::dvec2(first.texcoord);
        const glm::dvec3 placed = glm::dvec3(first.position) + glm::dvec3(first.tangent) * d.x +
                                  glm::dvec3(first.bitangent) * d.y;
        if (!(glm::length(placed - glm::dvec3(v.position)) <= tolerance)) return false;
    }
    return true;
}

std::optional<FlatPatch> flatPatchOf(const MeshData& data) {
    if (!isFlatPatch(data)) return std::nullopt;
    const Vertex& first = data.vertices.front();
    glm::vec2 lo = first.texcoord, hi = first.texcoord;
    for (const Vertex& v : data.vertices) {
        lo = glm::min(lo, v.texcoord);
        hi = glm::max(hi, v.texcoord);
    }
    const glm::dvec3 t(first.tangent), b(first.bitangent);
    const glm::dvec3 origin = glm::dvec3(first.position) - t * double(first.texcoord.x) - b * double(first.texcoord.y);
    auto at = [&](double u, double v) { return glm::vec3(origin + t * u + b * v); };
    return FlatPatch{.origin = glm::vec3(origin),
                     .tangent = first.tangent,
                     .bitangent = first.bitangent,
                     .normal = glm::normalize(first.normal),
                     .corners = {at(lo.x, lo.y), at(hi.x, lo.y), at(hi.x, hi.y), at(lo.x, hi.y)},
                     .texcoordMin = lo,
                     .texcoordMax = hi};
}

namespace {
/// `data` once MeshData::validate and its claims (closed, convex) hold: what a mesh is made of.
const MeshData& checkedMesh(const MeshData& data) {
    checkMeshClaims(data);
    return data;
}
} // namespace

Mesh::Mesh(const MeshData& data)
    : vertices_(GlBuffer::create()), indices_(GlBuffer::create()),
      vao_(GlVertexArray::create()), indexCount_(static_cast<GLsizei>(data.indices.size())),
      patch_(flatPatchOf(checkedMesh(data))), convex_(data.convex || patch_.has_value()), closed_(data.closed) {
    // The bounds: the box's centre, and the farthest vertex from it.
    const auto [lo, hi] = positionBox(data);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    double radius = 0.0;
    for (const Vertex& v : data.vertices) radius = std::max(radius, glm::length(glm::dvec3(v.position) - centre));
    bounds_ = glm::vec4(glm::vec3(centre), float(radius * (1.0 + 1e-6)));
    HFX_GL_CHECK(glNamedBufferStorage(vertices_.id(), data.vertices.size() * sizeof(Vertex),
                         data.vertices.data(), 0));
    HFX_GL_CHECK(glNamedBufferStorage(indices_.id(), data.indices.size() * sizeof(uint32_t),
                         data.indices.data(), 0));
    const GLuint vao = vao_.id();
    glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, indices_.id());
    auto attribute = [vao](GLuint location, GLint components, size_t offset) {
        glEnableVertexArrayAttrib(vao, location);
        glVertexArrayAttribFormat(vao, location, components, GL_FLOAT, GL_FALSE,
                                  static_cast<GLuint>(offset));
        glVertexArrayAttribBinding(vao, location, 0);
    };
    attribute(0, 3, offsetof(Vertex, position));
    attribute(1, 3, offsetof(Vertex, normal));
    attribute(2, 3, offsetof(Vertex, tangent));
    attribute(3, 3, offsetof(Vertex, bitangent));
    attribute(4, 2, offsetof(Vertex, texcoord));
}

void Mesh::draw() const {
    glBindVertexArray(vao_.id());
    HFX_GL_CHECK(glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr));
    glBindVertexArray(0);
}

} // namespace hfx
