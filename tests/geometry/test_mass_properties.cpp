#include <gtest/gtest.h>

#include "test_meshes_util.h"
#include "wheelsim/geometry/mass_properties.h"
#include "wheelsim/geometry/mesh_error.h"

using namespace wheelsim::geometry;
using test_meshes::box;
using test_meshes::transformed;

TEST(MassProperties, UnitCube) {
  const MassProperties p = mass_properties(box(1, 1, 1), 1000.0);
  EXPECT_NEAR(p.volume_m3, 1.0, 1e-14);
  EXPECT_NEAR(p.mass_kg, 1000.0, 1e-11);
  EXPECT_TRUE(p.centroid_m.isApprox(Eigen::Vector3d(0.5, 0.5, 0.5), 1e-14));
  // Cube about its centroid: m a^2 / 6 on the diagonal, no products of inertia.
  const Eigen::Matrix3d expected = Eigen::Matrix3d::Identity() * 1000.0 / 6.0;
  EXPECT_LT((p.inertia_about_centroid_kg_m2 - expected).norm(), 1e-10);
}

TEST(MassProperties, OffsetRotatedBox) {
  const double a = 0.3, b = 0.5, c = 1.2, rho = 7850.0;
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()) *
                             Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  const Eigen::Vector3d t(5.0, -3.0, 12.0);
  const MassProperties p = mass_properties(transformed(box(a, b, c), R, t), rho);
  const double m = rho * a * b * c;
  EXPECT_NEAR(p.volume_m3, a * b * c, 1e-12);
  EXPECT_NEAR(p.mass_kg, m, 1e-8);
  EXPECT_LT((p.centroid_m - (R * Eigen::Vector3d(a / 2, b / 2, c / 2) + t)).norm(), 1e-12);
  const Eigen::Matrix3d body =
      Eigen::Vector3d(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)
          .asDiagonal();
  const Eigen::Matrix3d expected = R * body * R.transpose();
  EXPECT_LT((p.inertia_about_centroid_kg_m2 - expected).norm(), 1e-9 * expected.norm());
}

TEST(MassProperties, CentroidOfShiftedMeshMovesWithIt) {
  const Eigen::Vector3d shift(-2.5, 0.75, 100.0);
  const MassProperties p0 = mass_properties(box(0.2, 0.4, 0.6), 1.0);
  const MassProperties p1 =
      mass_properties(transformed(box(0.2, 0.4, 0.6), Eigen::Matrix3d::Identity(), shift), 1.0);
  EXPECT_LT((p1.centroid_m - (p0.centroid_m + shift)).norm(), 1e-12);
  EXPECT_LT((p1.inertia_about_centroid_kg_m2 - p0.inertia_about_centroid_kg_m2).norm(), 1e-12);
}

TEST(MassProperties, ParallelAxis) {
  const MassProperties p = mass_properties(box(1, 2, 3), 2.0); // mass 12 kg
  const Eigen::Matrix3d I0 = inertia_about_point(p, Eigen::Vector3d::Zero());
  // About the corner at the origin: I_xx = m (b^2 + c^2) / 3.
  EXPECT_NEAR(I0(0, 0), 12.0 * (4 + 9) / 3.0, 1e-10);
  // Product of inertia about the corner: -m a b / 4.
  EXPECT_NEAR(I0(0, 1), -12.0 * 1 * 2 / 4.0, 1e-10);
}

TEST(MassProperties, RejectsInsideOutMeshAndBadDensity) {
  TriangleMesh m = box(1, 1, 1);
  EXPECT_THROW(mass_properties(m, 0.0), MeshError);
  for (auto &t : m.triangles)
    std::swap(t[1], t[2]);
  EXPECT_THROW(mass_properties(m, 1.0), MeshError);
}
