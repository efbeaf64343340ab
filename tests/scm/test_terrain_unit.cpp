// Unit tests of ScmTerrain through its API: exact wheel intersection, a flat plate against the
// Bekker law with b = 2A/L, input validation, sampling.
#include "scm_test_util.h"

#include "wheelsim/scm/scm_terrain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

namespace wheelsim::scm {
namespace {

ScmSettings no_bulldozing(double delta) {
  ScmSettings s;
  s.grid_spacing_m = delta;
  s.bulldozing.enabled = false;
  return s;
}

WheelPose at(const Eigen::Vector3d &p, double pitch_rad = 0.0) {
  WheelPose b;
  b.p_WB_W = p;
  b.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()));
  return b;
}

// Lowest z of the rotated, translated polygon (the faceted rim of make_cylinder, seen along the
// axle) at abscissa x, computed from the polygon's edges alone (no triangles, no grid).
double polygon_bottom(double R, int around, double pitch, const Eigen::Vector3d &c, double x) {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d Rot = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (int i = 0; i < around; ++i) {
    const double a0 = 2.0 * M_PI * i / around, a1 = 2.0 * M_PI * (i + 1) / around;
    const Eigen::Vector3d p0 = Rot * Eigen::Vector3d(R * std::cos(a0), 0, R * std::sin(a0)) + c;
    const Eigen::Vector3d p1 = Rot * Eigen::Vector3d(R * std::cos(a1), 0, R * std::sin(a1)) + c;
    const double lo = std::min(p0.x(), p1.x()), hi = std::max(p0.x(), p1.x());
    if (x < lo || x > hi || hi == lo)
      continue;
    const double t = (x - p0.x()) / (p1.x() - p0.x());
    best = std::min(best, p0.z() + t * (p1.z() - p0.z()));
  }
  return best;
}

TEST(Intersection, NodeHeightsEqualFacetedCylinderChord) {
  // Coarse facets (90 around: up to 0.3 mm from the circle) so the test tells the exact chord of
  // the mesh from the circle and from any approximate ray cast.
  const double R = 0.5, w = 0.3, delta = 0.01, pitch = 0.1234;
  const int around = 90;
  const Eigen::Vector3d c(0.0137, 0.0041, R - 0.045);
  ScmTerrain t(test::lete_sand(), no_bulldozing(delta), test::make_cylinder(R, w, around, 3));
  const ScmContact contact = t.advance(at(c, pitch), 1e-3);
  ASSERT_GT(contact.contact_nodes, 100);
  const FieldMap h = t.sample(Field::height, -0.5, 0.5, -0.3, 0.3);
  int compared = 0, expected_contacts = 0;
  double worst = 0.0;
  for (std::size_t r = 0; r < h.rows; ++r)
    for (std::size_t k = 0; k < h.cols; ++k) {
      const double x = h.x0_m + k * delta, y = h.y0_m + r * delta;
      const double dy = std::abs(y - c.y());
      if (std::abs(dy - 0.5 * w) < 1e-9)
        continue; // on the side edge: ambiguous by definition
      const double z = dy < 0.5 * w ? polygon_bottom(R, around, pitch, c, x)
                                    : std::numeric_limits<double>::infinity();
      const double got = h.values[r * h.cols + k];
      if (z < 0.0) {
        ++expected_contacts;
        worst = std::max(worst, std::abs(got - z));
        ++compared;
      } else {
        EXPECT_EQ(got, 0.0) << "node off the wheel moved at x = " << x << ", y = " << y;
      }
    }
  EXPECT_EQ(contact.contact_nodes, expected_contacts);
  EXPECT_GT(compared, 100);
  EXPECT_LT(worst, 1e-9) << "largest |node height − facet chord| [m]";
  std::printf("  %d nodes compared, largest |height - facet chord| = %.3e m\n", compared, worst);
}

TEST(Intersection, FlatPlateMatchesBekkerWithPatchWidth) {
  // A 0.4 m × 0.4 m plate pressed 30 mm: all nodes under it at the same sinkage; the force must
  // be nodes × Δ² × (kc/b + kφ) z^n with b = 2A/L of the hull of the node points.
  const double delta = 0.02, z = 0.03;
  SoilParameters soil = test::lete_sand();
  soil.damping_R = 0.0;
  ScmTerrain t(soil, no_bulldozing(delta), test::make_box(0.4, 0.4, 0.2));
  const ScmContact f = t.advance(at(Eigen::Vector3d(0.001, 0.003, 0.1 - z)), 1e-3);
  // Nodes strictly inside x ∈ (−0.199, 0.201), y ∈ (−0.197, 0.203): 20 × 20.
  ASSERT_EQ(f.contact_nodes, 400);
  ASSERT_EQ(f.patches, 1);
  const double side = 19 * delta, b = 2.0 * side * side / (4.0 * side);
  const double sigma = (soil.Bekker_Kc / b + soil.Bekker_Kphi) * std::pow(z, soil.Bekker_n);
  const double expected = 400 * delta * delta * sigma;
  EXPECT_NEAR(f.wrench.f_B_W.z(), expected, 1e-9 * expected);
  EXPECT_NEAR(f.wrench.f_B_W.x(), 0.0, 1e-9 * expected);
  // Moment about Bo: node centroid (0.01, 0.01) − Bo (0.001, 0.003), at z − Bo_z = −0.03 − 0.07.
  EXPECT_NEAR(f.wrench.t_B_W.x(), 0.007 * expected, 1e-9 * expected);
  EXPECT_NEAR(f.wrench.t_B_W.y(), -0.009 * expected, 1e-9 * expected);
  // Pressure map and plastic sinkage.
  const FieldMap p = t.sample(Field::pressure, 0.0, 0.0, 0.0, 0.0);
  ASSERT_EQ(p.values.size(), 1u);
  EXPECT_NEAR(p.values[0], sigma, 1e-9 * sigma);
}

TEST(MultiPass, PlasticSinkageAndYieldStay) {
  // Plate pressed to 30 mm, lifted, pressed again: the second pass meets the compacted soil. At
  // the same depth it reloads elastically to the old yield (no new plastic sinkage); deeper, it
  // continues on the Bekker curve. Tolerance: round-off (1e-9 relative).
  const double delta = 0.02;
  SoilParameters soil = test::lete_sand();
  soil.damping_R = 0.0;
  ScmTerrain t(soil, no_bulldozing(delta), test::make_box(0.4, 0.4, 0.2));
  const Eigen::Vector3d c(0.001, 0.003, 0.07);
  const double f1 = t.advance(at(c), 1e-3).wrench.f_B_W.z();
  const double zp1 = t.sample(Field::plastic_sinkage, 0, 0, 0, 0).values[0];
  EXPECT_EQ(t.advance(at(c + Eigen::Vector3d(0, 0, 0.5)), 1e-3).contact_nodes, 0);
  EXPECT_EQ(t.sample(Field::pressure, 0, 0, 0, 0).values[0], 0.0) << "σ is 0 off contact";
  // Just above the plastic level: no contact.
  EXPECT_EQ(t.advance(at(c + Eigen::Vector3d(0, 0, 0.03 - zp1 + 1e-6)), 1e-3).contact_nodes, 0);
  const double f2 = t.advance(at(c), 1e-3).wrench.f_B_W.z();
  EXPECT_NEAR(f2, f1, 1e-9 * f1) << "elastic reload to the yield pressure";
  EXPECT_NEAR(t.sample(Field::plastic_sinkage, 0, 0, 0, 0).values[0], zp1, 1e-15);
  const double f3 = t.advance(at(c - Eigen::Vector3d(0, 0, 0.01)), 1e-3).wrench.f_B_W.z();
  const double side = 19 * delta, b = side / 2.0;
  const double sigma = (soil.Bekker_Kc / b + soil.Bekker_Kphi) * std::pow(0.04, soil.Bekker_n);
  EXPECT_NEAR(f3, 400 * delta * delta * sigma, 1e-9 * f3);
  EXPECT_GT(t.sample(Field::plastic_sinkage, 0, 0, 0, 0).values[0], zp1 + 0.009);
}

TEST(Intersection, WheelAboveSoilTouchesNothingAndStoresNothing) {
  ScmTerrain t(test::lete_sand(), ScmSettings{}, test::make_cylinder(0.5, 0.3, 60));
  const ScmContact f = t.advance(at(Eigen::Vector3d(0, 0, 0.5001)), 1e-3);
  EXPECT_EQ(f.contact_nodes, 0);
  EXPECT_EQ(f.wrench.f_B_W.norm(), 0.0);
  EXPECT_EQ(t.stored_nodes(), 0u);
  EXPECT_EQ(t.sample(Field::height).values.size(), 0u);
  EXPECT_EQ(t.volume_change_m3(), 0.0);
}

TEST(Intersection, DomainBoundsLimitTheSoil) {
  ScmSettings s = no_bulldozing(0.02);
  s.domain_m = Eigen::Vector4d(0.0, 10.0, -5.0, 5.0); // soil only at x ≥ 0
  ScmTerrain t(test::lete_sand(), s, test::make_box(0.4, 0.4, 0.2));
  const ScmContact f = t.advance(at(Eigen::Vector3d(0.001, 0.003, 0.07)), 1e-3);
  EXPECT_EQ(f.contact_nodes, 220); // x = 0 .. 0.20 → 11 columns × 20 rows
}

void expect_invalid(const std::function<void()> &make, const std::string &needle) {
  try {
    make();
    ADD_FAILURE() << "no exception, expected one mentioning '" << needle << "'";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(Validation, BadSettingsNameTheSettingAndRange) {
  const auto mesh = test::make_box(0.1, 0.1, 0.1);
  const SoilParameters soil = test::lete_sand();
  auto with = [&](auto edit) {
    return [=] {
      ScmSettings s;
      edit(s);
      ScmTerrain t(soil, s, mesh);
    };
  };
  expect_invalid(with([](ScmSettings &s) { s.grid_spacing_m = -1; }),
                 "scm grid_spacing must be > 0 m, got -1");
  expect_invalid(with([](ScmSettings &s) { s.bulldozing.erosion_angle_deg = 90; }),
                 "erosion_angle must be in (0, 90) deg, got 90");
  expect_invalid(with([](ScmSettings &s) { s.bulldozing.flow_factor = -0.5; }),
                 "flow_factor must be >= 0, got -0.5");
  expect_invalid(with([](ScmSettings &s) { s.bulldozing.erosion_rings = 0; }),
                 "erosion_rings must be >= 1, got 0");
  expect_invalid(with([](ScmSettings &s) { s.bulldozing.erosion_iterations = -1; }),
                 "erosion_iterations must be >= 0, got -1");
  expect_invalid(with([](ScmSettings &s) { s.domain_m = Eigen::Vector4d(1, 0, 0, 1); }),
                 "domain x_max");
  auto soil_with = [&](auto edit) {
    return [=] {
      SoilParameters s = soil;
      edit(s);
      ScmTerrain t(s, ScmSettings{}, mesh);
    };
  };
  expect_invalid(soil_with([](SoilParameters &s) { s.Bekker_n = 0; }),
                 "scm soil Bekker_n must be > 0");
  expect_invalid(soil_with([](SoilParameters &s) { s.Janosi_shear = 0; }), "Janosi_shear");
  expect_invalid(soil_with([](SoilParameters &s) { s.elastic_K = -1; }), "elastic_K");
  expect_invalid(soil_with([](SoilParameters &s) { s.Mohr_friction = 2.0; }), "Mohr_friction");
  ScmTerrain t(soil, ScmSettings{}, mesh);
  expect_invalid([&] { t.advance(WheelPose{}, 0.0); }, "scm time step dt must be > 0 s, got 0");
}

TEST(Fields, NamesAndUnits) {
  EXPECT_STREQ(to_string(Field::pressure), "pressure");
  EXPECT_STREQ(unit_of(Field::pressure), "Pa");
  EXPECT_STREQ(unit_of(Field::shear_displacement), "m");
}

} // namespace
} // namespace wheelsim::scm
