#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/Uid.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace hfx {
namespace {

TEST(Plane, TangentsAreTexcoordDerivatives) {
    const MeshData plane = makePlane({.size = 6.0f, .texcoordScale = 3.0f, .subdivisions = 4});
    ASSERT_EQ(plane.vertices.size(), 25u);
    ASSERT_EQ(plane.indices.size(), 4u * 4u * 6u);
    const Vertex& a = plane.vertices[0];
    const Vertex& b = plane.vertices[1];  // next along u
    const Vertex& c = plane.vertices[5];  // next along v
    // dP/du: position change over texcoord change, both measured between neighbours.
    EXPECT_EQ((b.position - a.position) / (b.texcoord.x - a.texcoord.x), a.tangent);
    EXPECT_EQ((c.position - a.position) / (c.texcoord.y - a.texcoord.y), a.bitangent);
    // Right-handed: T x B points along the normal.
    EXPECT_GT(glm::dot(glm::cross(a.tangent, a.bitangent), a.normal), 0.0f);
    // Triangles wind counter-clockwise seen from +Y.
    const glm::vec3 p0 = plane.vertices[plane.indices[0]].position;
    const glm::vec3 p1 = plane.vertices[plane.indices[1]].position;
    const glm::vec3 p2 = plane.vertices[plane.indices[2]].position;
    EXPECT_GT(glm::cross(p1 - p0, p2 - p0).y, 0.0f);
}

TEST(Plane, BadConfigurationNamesTheField) {
    try {
        makePlane({.size = -1.0f});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("PlaneConfig.size"), std::string::npos);
    }
    EXPECT_THROW(makePlane({.subdivisions = 0}), Error);
}

TEST(Sphere, TangentsAreTexcoordDerivativesAndFaceOutwards) {
    const SphereConfig config{.radius = 2.0f, .segments = 64, .rings = 32};
    const MeshData sphere = makeSphere(config);
    const int row = config.segments + 1;
    ASSERT_EQ(sphere.vertices.size(), size_t(row * (config.rings + 1)));
    for (int j = 1; j < config.rings - 1; ++j)
        for (int i = 0; i < config.segments; ++i) {
            const Vertex& a = sphere.vertices[j * row + i];
            const Vertex& b = sphere.vertices[j * row + i + 1];
            const Vertex& c = sphere.vertices[(j + 1) * row + i];
            ASSERT_NEAR(glm::length(a.position), 2.0f, 1e-5f);
            // Central differences of the exact parametrisation agree with T and B to O(h^2):
            // compare the one-sided difference with the average of the two ends' derivatives.
            const glm::vec3 du = (b.position - a.position) / (b.texcoord.x - a.texcoord.x);
            const glm::vec3 dv = (c.position - a.position) / (c.texcoord.y - a.texcoord.y);
            ASSERT_LT(glm::length(du - 0.5f * (a.tangent + b.tangent)), 2e-2f * glm::length(a.tangent) + 1e-3f);
            ASSERT_LT(glm::length(dv - 0.5f * (a.bitangent + c.bitangent)), 2e-2f * glm::length(a.bitangent));
            ASSERT_GT(glm::dot(glm::cross(a.tangent, a.bitangent), a.position), 0.0f) << i << "," << j;
            const glm::vec3 p0 = sphere.vertices[sphere.indices[6 * (j * config.segments + i)]].position;
            const glm::vec3 p1 = sphere.vertices[sphere.indices[6 * (j * config.segments + i) + 1]].position;
            const glm::vec3 p2 = sphere.vertices[sphere.indices[6 * (j * config.segments + i) + 2]].position;
            ASSERT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), p0 + p1 + p2), 0.0f) << "winding at " << i << "," << j;
        }
    // The seam doubles its vertices: u = 0 and u = 1 share positions.
    EXPECT_LT(glm::length(sphere.vertices[row * 10].position - sphere.vertices[row * 10 + config.segments].position), 1e-5f);
    EXPECT_THROW(makeSphere({.segments = 2}), Error);
    EXPECT_THROW(makeSphere({.radius = 0.0f}), Error);
}

TEST(Cylinder, TangentsAreTexcoordDerivativesFacingOutwardsAndItIsConvexNotClosed) {
    const CylinderConfig config{.radius = 0.6f, .height = 3.0f, .segments = 48, .texcoordScale = {2.0f, 1.5f}};
    const MeshData cylinder = makeCylinder(config);
    const int row = config.segments + 1;
    ASSERT_EQ(cylinder.vertices.size(), size_t(2 * row));
    ASSERT_EQ(cylinder.indices.size(), size_t(6 * config.segments));
    for (int i = 0; i < config.segments; ++i) {
        const Vertex& a = cylinder.vertices[i];
        const Vertex& b = cylinder.vertices[i + 1];
        const Vertex& c = cylinder.vertices[row + i];
        ASSERT_NEAR(glm::length(glm::vec2(a.position.x, a.position.z)), 0.6f, 1e-6f);
        ASSERT_FLOAT_EQ(a.position.y, -1.5f);
        ASSERT_FLOAT_EQ(c.position.y, 1.5f);
        // The texcoords' derivatives: a chord around against the two ends' tangents (O(h^2)),
        // exactly along the height.
        const glm::vec3 du = (b.position - a.position) / (b.texcoord.x - a.texcoord.x);
        ASSERT_LT(glm::length(du - 0.5f * (a.tangent + b.tangent)), 2e-3f * glm::length(a.tangent));
        ASSERT_LT(glm::length((c.position - a.position) / (c.texcoord.y - a.texcoord.y) - a.bitangent), 1e-5f);
        ASSERT_GT(glm::dot(glm::normalize(glm::cross(a.tangent, a.bitangent)), a.normal), 0.9999f) << i;
        ASSERT_NEAR(glm::dot(a.normal, glm::vec3(a.position.x, 0.0f, a.position.z)) / 0.6f, 1.0f, 1e-5f);
        const glm::vec3 p0 = cylinder.vertices[cylinder.indices[6 * i]].position;
        const glm::vec3 p1 = cylinder.vertices[cylinder.indices[6 * i + 1]].position;
        const glm::vec3 p2 = cylinder.vertices[cylinder.indices[6 * i + 2]].position;
        ASSERT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), glm::vec3(p0.x, 0.0f, p0.z)), 0.0f) << "winding at " << i;
    }
    EXPECT_FLOAT_EQ(cylinder.vertices[config.segments].texcoord.x, 2.0f);
    EXPECT_FLOAT_EQ(cylinder.vertices[row].texcoord.y, 1.5f);
    EXPECT_TRUE(cylinder.convex);
    EXPECT_FALSE(cylinder.closed);
    EXPECT_TRUE(isConvex(cylinder));
    EXPECT_NO_THROW(checkMeshClaims(cylinder));
    EXPECT_FALSE(isFlatPatch(cylinder));
    EXPECT_EQ(test::messageOf([] { makeCylinder({.segments = 2}); }), "CylinderConfig needs 3..4096 segments, got 2");
    EXPECT_EQ(test::messageOf([] { makeCylinder({.height = 0.0f}); }),
              "CylinderConfig.radius and height must be positive, got 0.5 and 0");
    EXPECT_EQ(test::messageOf([] { makeCylinder({.texcoordScale = {1.0f, -1.0f}}); }),
              "CylinderConfig.texcoordScale must be positive, got 1, -1");
}

TEST(FlatPatch, PlanesAreOneFlatPatchAndSpheresAndBentOrMislabelledPlanesAreNot) {
    EXPECT_TRUE(isFlatPatch(makePlane({})));
    EXPECT_TRUE(isFlatPatch(makePlane({.size = 40.0f, .texcoordScale = 7.0f, .subdivisions = 16})));
    EXPECT_FALSE(isFlatPatch(makeSphere({})));
    EXPECT_FALSE(isFlatPatch(MeshData{}));
    MeshData bent = makePlane({.subdivisions = 4});
    bent.vertices[7].position.y += 0.01f; // off the plane
    EXPECT_FALSE(isFlatPatch(bent));
    MeshData slid = makePlane({.subdivisions = 4});
    slid.vertices[7].texcoord.x += 0.01f; // texcoords no longer where the frame puts the vertex
    EXPECT_FALSE(isFlatPatch(slid));
    MeshData turned = makePlane({.subdivisions = 4});
    turned.vertices[7].tangent = glm::vec3(0.0f, 0.0f, 2.0f); // a second texture frame
    EXPECT_FALSE(isFlatPatch(turned));
}

TEST(Convex, PlanesAndSpheresSayTheyAreConvexAndAreAndBumpsAndFlippedFacesAreNot) {
    // MeshData::convex is what the exact tracer's compute pass trusts: one fragment per pixel.
    for (const MeshData& mesh : {makePlane({}), makePlane({.subdivisions = 8}), makeSphere({}),
                                 makeSphere({.radius = 3.0f, .segments = 7, .rings = 3})}) {
        EXPECT_TRUE(mesh.convex);
        EXPECT_TRUE(isConvex(mesh));
    }
    MeshData bump = makeSphere({.segments = 12, .rings = 6});
    bump.vertices[30].position *= 1.05f; // out past its neighbours' faces
    EXPECT_FALSE(isConvex(bump));
    MeshData dent = makeSphere({.segments = 12, .rings = 6});
    dent.vertices[30].position *= 0.9f; // its own faces tilt in: the neighbours' points lie in front
    EXPECT_FALSE(isConvex(dent));
    MeshData inward = makeSphere({.segments = 12, .rings = 6});
    for (size_t t = 0; t < inward.indices.size(); t += 3) std::swap(inward.indices[t + 1], inward.indices[t + 2]);
    EXPECT_FALSE(isConvex(inward)) << "faces turned inwards";
    MeshData valley = makePlane({.subdivisions = 2});
    valley.vertices[4].position.y -= 0.1f; // its rim lies in front of its faces
    EXPECT_FALSE(isConvex(valley));
    EXPECT_FALSE(isConvex(MeshData{}));
    EXPECT_FALSE(MeshData{}.convex) << "a mesh of one's own is not trusted unless it says so";
}

/// What checkMeshClaims says of `mesh`: its error's message, or "(no error)".
std::string claimsMessage(const MeshData& mesh) {
    return test::messageOf([&] { checkMeshClaims(mesh); });
}

TEST(Convex, AMeshsClaimsAreCheckedAtItsEdgesAndAFalseOneNamesTheEdge) {
    // Mesh's constructor calls checkMeshClaims: the renderer culls a closed mesh's back faces and
    // walks a convex one's rays in the compute pass, so a false claim would show as wrong pixels.
    for (const MeshData& mesh : {makePlane({}), makePlane({.subdivisions = 8}), makeSphere({}),
                                 makeSphere({.radius = 3.0f, .segments = 7, .rings = 3})})
        EXPECT_NO_THROW(checkMeshClaims(mesh));
    MeshData holed = makeSphere({.segments = 12, .rings = 6});
    // (Triangle 83: ring 3's quad 5, away from the poles, whose first triangles have no area.)
    holed.indices.erase(holed.indices.begin() + 249, holed.indices.begin() + 252); // one triangle gone
    const std::string hole = claimsMessage(holed);
    EXPECT_NE(hole.find("MeshData::closed, but the edge from ("), std::string::npos) << hole;
    EXPECT_NE(hole.find("has 1 face, not 2 (a hole)"), std::string::npos) << hole;
    std::printf("[claims] %s\n", hole.c_str());
    MeshData turned = makeSphere({.segments = 12, .rings = 6});
    std::swap(turned.indices[250], turned.indices[251]); // one triangle wound the other way
    EXPECT_NE(claimsMessage(turned).find("wound the same way"), std::string::npos) << claimsMessage(turned);
    MeshData dent = makeSphere({.segments = 12, .rings = 6});
    dent.vertices[30].position *= 0.9f;
    EXPECT_NE(claimsMessage(dent).find("MeshData::convex, but at the edge"), std::string::npos) << claimsMessage(dent);
    MeshData valley = makePlane({.subdivisions = 2});
    valley.vertices[4].position.y -= 0.1f;
    EXPECT_NE(claimsMessage(valley).find("MeshData::convex"), std::string::npos) << claimsMessage(valley);
    valley.convex = false; // said of none: nothing to check
    EXPECT_EQ(claimsMessage(valley), "(no error)");
}

/// `b`'s triangles moved by `offset` and added to `a`'s, the claims `a`'s.
MeshData joined(MeshData a, const MeshData& b, glm::vec3 offset) {
    const auto base = uint32_t(a.vertices.size());
    for (Vertex v : b.vertices) {
        v.position += offset;
        a.vertices.push_back(v);
    }
    for (const uint32_t i : b.indices) a.indices.push_back(base + i);
    return a;
}

TEST(Convex, AConvexClaimOnFacesInPartsThatShareNoEdgeIsCheckedWhole) {
    // Each of two spheres side by side is convex at every edge, and each is closed: only the whole
    // can tell that their front faces overlap on the screen. Parts that lie on one convex solid
    // (a sphere's two caps without the band between them) or in one plane (a plane in two
    // pieces) are convex; past 2e8 face-vertex pairs the claim is refused by name, not checked
    // for minutes.
    const MeshData sphere = makeSphere({.segments = 12, .rings = 6});
    const MeshData pair = joined(sphere, sphere, {3.0f, 0.0f, 0.0f});
    const std::string twoParts = "MeshData::convex, but its faces form 2 parts that share no edge, "
                                 "and the point (";
    EXPECT_NE(claimsMessage(pair).find(twoParts), std::string::npos) << claimsMessage(pair);
    std::printf("[claims] %s\n", claimsMessage(pair).c_str());
    MeshData closedOnly = pair;
    closedOnly.convex = false;
    EXPECT_EQ(claimsMessage(closedOnly), "(no error)") << "two closed solids are closed";

    MeshData caps = sphere;
    caps.closed = false;
    caps.indices.clear();
    for (size_t t = 0; t < sphere.indices.size(); t += 3) {
        float y = 0.0f;
        for (size_t k = 0; k < 3; ++k) y += sphere.vertices[sphere.indices[t + k]].position.y / 3.0f;
        if (std::abs(y) > 0.45f)
            for (size_t k = 0; k < 3; ++k) caps.indices.push_back(sphere.indices[t + k]);
    }
    ASSERT_LT(caps.indices.size(), sphere.indices.size());
    EXPECT_EQ(claimsMessage(caps), "(no error)") << "two caps of one sphere";
    const MeshData pieces = joined(makePlane({}), makePlane({}), {3.0f, 0.0f, 0.0f});
    EXPECT_EQ(claimsMessage(pieces), "(no error)") << "a plane in two pieces";
    const MeshData step = joined(makePlane({}), makePlane({}), {3.0f, 0.5f, 0.0f});
    EXPECT_NE(claimsMessage(step).find("2 parts that share no edge"), std::string::npos) << claimsMessage(step);

    const MeshData fine = makeSphere({.segments = 128, .rings = 64});
    const MeshData large = joined(fine, fine, {3.0f, 0.0f, 0.0f});
    EXPECT_NE(claimsMessage(large).find("too many to check"), std::string::npos) << claimsMessage(large);
}

/// A sheet 1 high rolled `turns` times about the y axis, its radius growing from 1 by `growth`
/// a turn, facing out: convex at every edge.
MeshData scroll(double turns, double growth) {
    constexpr double pi = 3.14159265358979323846;
    MeshData mesh;
    const int segments = int(std::ceil(turns * 24.0));
    for (int j = 0; j <= 1; ++j)
        for (int i = 0; i <= segments; ++i) {
            const double a = 2.0 * pi * turns * i / segments, r = 1.0 + growth * a / (2.0 * pi);
            const double c = std::cos(a), s = std::sin(a);
            Vertex v;
            v.position = glm::vec3(glm::dvec3(r * c, j, -r * s));
            v.normal = glm::vec3(glm::dvec3(c, 0.0, -s));
            v.tangent = glm::vec3(glm::dvec3(-s, 0.0, -c));
            v.bitangent = glm::vec3(0.0f, 1.0f, 0.0f);
            v.texcoord = {float(i) / float(segments), float(j)};
            mesh.vertices.push_back(v);
        }
    const auto row = uint32_t(segments + 1);
    for (uint32_t i = 0; i < uint32_t(segments); ++i) {
        const uint32_t a = i, b = a + 1, c = a + row, d = c + 1;
        mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
    mesh.convex = true;
    return mesh;
}

TEST(Convex, AnOpenSheetConvexAtEveryEdgeIsCheckedWhole) {
    // A sheet rolled one and a half turns is convex at every edge, in one part, and open: its
    // outer turn's faces lie over its inner turn's on the screen. Half a turn of it is convex.
    EXPECT_EQ(claimsMessage(scroll(0.5, 0.05)), "(no error)") << "half a turn";
    EXPECT_EQ(claimsMessage(makeCylinder({})), "(no error)") << "an open tube";
    const std::string rolled = claimsMessage(scroll(1.5, 0.05));
    EXPECT_NE(rolled.find("MeshData::convex, but the point ("), std::string::npos) << rolled;
    EXPECT_NE(rolled.find("wraps past one convex solid"), std::string::npos) << rolled;
    std::printf("[claims] %s\n", rolled.c_str());
    MeshData unclaimed = scroll(1.5, 0.05);
    unclaimed.convex = false;
    EXPECT_EQ(claimsMessage(unclaimed), "(no error)");
}

} // namespace
} // namespace hfx

namespace hfx {
namespace {

TEST(FlatPatch, APlaneKeepsItsTextureFrameAndCornersAndNothingElseHasOne) {
    // makePlane: u along +X, v along -Z, texcoords 0..scale across a size-wide square. The patch
    // must give its frame (the position at texcoords (0, 0), dP/du, dP/dv, +Y), its corners and its
    // texcoords' box; a sphere and a plane with one vertex lifted have none.
    const PlaneConfig config{.size = 3.0f, .texcoordScale = 2.0f, .subdivisions = 3};
    const std::optional<FlatPatch> patch = flatPatchOf(makePlane(config));
    ASSERT_TRUE(patch);
    const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-5f; };
    EXPECT_TRUE(near(patch->origin, {-1.5f, 0.0f, 1.5f}));
    EXPECT_TRUE(near(patch->tangent, {1.5f, 0.0f, 0.0f}));
    EXPECT_TRUE(near(patch->bitangent, {0.0f, 0.0f, -1.5f}));
    EXPECT_TRUE(near(patch->normal, {0.0f, 1.0f, 0.0f}));
    const glm::vec3 corners[4] = {{-1.5f, 0.0f, 1.5f}, {1.5f, 0.0f, 1.5f}, {1.5f, 0.0f, -1.5f}, {-1.5f, 0.0f, -1.5f}};
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(near(patch->corners[size_t(i)], corners[i])) << "corner " << i;
    EXPECT_EQ(patch->texcoordMin, glm::vec2(0.0f)) << "its texcoords' box";
    EXPECT_EQ(patch->texcoordMax, glm::vec2(2.0f));
    EXPECT_FALSE(flatPatchOf(makeSphere()));
    MeshData lifted = makePlane(config);
    lifted.vertices[5].position.y += 0.01f;
    EXPECT_FALSE(flatPatchOf(lifted));
}

TEST(MeshDataCheck, AFaultyMeshNamesItsFaultAndADegenerateTextureFrameIsAllowed) {
    // MeshData::validate, which the Mesh constructor calls before it uploads anything: a NaN or
    // an infinity in any attribute, or a normal of no direction, would reach the shader as a NaN
    // (it normalises the interpolated normal), a broken index as a read past the buffer.
    const auto message = [](const MeshData& mesh) { return test::messageOf([&] { mesh.validate(); }); };
    EXPECT_EQ(message(makePlane({.subdivisions = 3})), "(no error)");
    EXPECT_EQ(message(makeSphere({})), "(no error)") << "the poles' tangents are 0: a degenerate frame, allowed";
    MeshData noFrame = makePlane({});
    for (Vertex& v : noFrame.vertices) v.tangent = v.bitangent = glm::vec3(0.0f);
    EXPECT_EQ(message(noFrame), "(no error)") << "no texture frame at all: normal mapped, allowed";
    EXPECT_NE(message(MeshData{}).find("mesh needs triangles, got 0 vertices and 0 indices"), std::string::npos);
    MeshData ragged = makePlane({});
    ragged.indices.pop_back();
    EXPECT_NE(message(ragged).find("mesh needs triangles, got 4 vertices and 5 indices"), std::string::npos);
    MeshData past = makePlane({});
    past.indices[4] = 9;
    EXPECT_EQ(message(past), "mesh index 9 (entry 4) is out of range (4 vertices)");
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    struct Fault {
        void (*spoil)(Vertex&, float);
        float value;
        const char* expected;
    };
    const Fault faults[] = {
        {[](Vertex& v, float x) { v.position.y = x; }, nan, "mesh vertex 2: its position (-1, nan, -1) is not finite"},
        {[](Vertex& v, float x) { v.normal.x = x; }, inf, "mesh vertex 2: its normal (inf, 1, 0) is not finite"},
        {[](Vertex& v, float x) { v.tangent.z = x; }, -inf, "mesh vertex 2: its tangent (2, 0, -inf) is not finite"},
        {[](Vertex& v, float x) { v.bitangent.x = x; }, nan, "mesh vertex 2: its bitangent (nan, 0, -2) is not finite"},
        {[](Vertex& v, float x) { v.texcoord.y = x; }, nan, "mesh vertex 2: its texcoord (0, nan) is not finite"},
        {[](Vertex& v, float x) { v.normal = glm::vec3(x); }, 0.0f,
         "mesh vertex 2: its normal (0, 0, 0) has no direction (a unit normal is needed)"},
    };
    for (const Fault& fault : faults) {
        MeshData spoilt = makePlane({});
        fault.spoil(spoilt.vertices[2], fault.value);
        EXPECT_EQ(message(spoilt), fault.expected);
        // (makePlane's mesh says it is convex: its claims are checked, and the vertices first.)
        EXPECT_THROW(checkMeshClaims(spoilt), Error) << "the claims' check reads the vertices: it validates first";
    }
}

TEST(Uid, AMoveTakesTheIdentityAlongAndLeavesTheOwnerMovedFromANewOne) {
    // What the exact tracer keys a mesh's choices on (Mesh::uid; SurfaceTextures::uid for the
    // bounds): no two live owners share one, none is 0, none comes twice.
    Uid a, b;
    const std::uint64_t first = a.value(), second = b.value();
    EXPECT_NE(first, 0u);
    EXPECT_NE(first, second);
    Uid moved(std::move(a));
    EXPECT_EQ(moved.value(), first);
    EXPECT_NE(a.value(), first);
    EXPECT_NE(a.value(), second);
    b = std::move(moved);
    EXPECT_EQ(b.value(), first);
    EXPECT_NE(moved.value(), first);
    EXPECT_NE(moved.value(), a.value());
}

} // namespace
} // namespace hfx
