#include <cmath>

#include <gtest/gtest.h>

#include "test_meshes_util.h"
#include "wheelsim/geometry/mesh_check.h"

using namespace wheelsim::geometry;
using test_meshes::box;

TEST(CheckMesh, ValidBox) {
  const MeshReport r = check_mesh(box(1, 1, 1));
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors.front());
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.consistently_oriented());
  EXPECT_NEAR(r.signed_volume_m3, 1.0, 1e-14);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(CheckMesh, MissingTriangleIsOpen) {
  TriangleMesh m = box(1, 1, 1);
  m.triangles.pop_back();
  const MeshReport r = check_mesh(m);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.boundary_edges, 3);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_NE(r.errors.front().find("mesh is not closed: 3 boundary edges (first at vertex"),
            std::string::npos)
      << r.errors.front();
}

TEST(CheckMesh, FlippedTriangleIsInconsistent) {
  TriangleMesh m = box(1, 1, 1);
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.inconsistent_edges, 3);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_NE(r.errors.front().find("inconsistently oriented"), std::string::npos);
}

TEST(CheckMesh, InsideOutIsAnError) {
  TriangleMesh m = box(1, 1, 1);
  for (auto &t : m.triangles)
    std::swap(t[1], t[2]);
  const MeshReport r = check_mesh(m);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.consistently_oriented());
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors.front().find("inside out"), std::string::npos);
}

TEST(CheckMesh, NonFiniteVertexIsTheOnlyError) {
  TriangleMesh m = box(1, 1, 1);
  m.vertices_m[3].y() = std::nan("");
  const MeshReport r = check_mesh(m);
  ASSERT_EQ(r.errors.size(), 1u); // not also "inside out" or an implausible size
  EXPECT_NE(r.errors.front().find("vertex 3 has a coordinate that is not a finite number: (1, nan"),
            std::string::npos)
      << r.errors.front();
}

TEST(CheckMesh, MillimetreSizeSuggestsScale) {
  const MeshReport r = check_mesh(box(1234, 479, 1234));
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors.front().find("looks like millimetres: use scale 0.001"), std::string::npos)
      << r.errors.front();
}

TEST(CheckMesh, DegenerateTriangleIsAWarning) {
  TriangleMesh m = box(1, 1, 1);
  // A zero-area sliver glued on twice with opposite windings keeps the mesh closed.
  m.vertices_m.emplace_back(0.5, 0.0, 0.0);
  const int mid = static_cast<int>(m.vertices_m.size()) - 1;
  m.triangles.push_back({0, 1, mid});
  m.triangles.push_back({0, mid, 1});
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.degenerate_triangles.size(), 2u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings.front().find("2 degenerate triangles"), std::string::npos);
}
