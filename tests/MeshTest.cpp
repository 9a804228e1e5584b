#include "hfx/core/Error.h"
#include "hfx/core/Mesh.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

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

} // namespace
} // namespace hfx
