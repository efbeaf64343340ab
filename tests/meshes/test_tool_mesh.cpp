// The tool meshes of `wheel-mesh tool` (meshes/src/tool_*.{h,cpp}): closed, outward, and the
// volume, bounding box, centroid and inertia of the analytic solid.
#include <cmath>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "tool_builder.h"
#include "wheel_output.h"
#include "wheelsim/geometry/mesh_check.h"
#include "wheelsim/geometry/sphere_contact_index.h"

using namespace wheelsim::meshes;
using wheelsim::geometry::TriangleMesh;

namespace {

ToolSpec plate_rect(double lx, double ly, double t) {
  ToolSpec s;
  s.kind = ToolKind::plate_rect;
  s.lx_m = lx;
  s.ly_m = ly;
  s.height_m = t;
  return s;
}

ToolSpec plate_disc(double r, double t, int segments = 0) {
  ToolSpec s;
  s.kind = ToolKind::plate_disc;
  s.radius_m = r;
  s.height_m = t;
  s.segments = segments;
  return s;
}

ToolSpec frame(double lx, double ly, double wall, double h) {
  ToolSpec s;
  s.kind = ToolKind::frame;
  s.lx_m = lx;
  s.ly_m = ly;
  s.wall_m = wall;
  s.height_m = h;
  return s;
}

ToolSpec ring(double ri, double ro, double h, int segments = 0) {
  ToolSpec s;
  s.kind = ToolKind::ring;
  s.inner_radius_m = ri;
  s.radius_m = ro;
  s.height_m = h;
  s.segments = segments;
  return s;
}

ToolSpec with_max_edge(ToolSpec s, double e) {
  s.max_edge_m = e;
  return s;
}

/// Volume of the faceted tool: the round ones are regular n-gons inscribed in their circles,
/// area (n / 2) r^2 sin(2 pi / n).
double polygon_volume(const ToolSpec &s) {
  if (!s.round())
    return ideal_volume_m3(s);
  const double n = segment_count(s), f = 0.5 * n * std::sin(2.0 * M_PI / n);
  const double ri = s.kind == ToolKind::ring ? s.inner_radius_m : 0.0;
  return f * (s.radius_m * s.radius_m - ri * ri) * s.height_m;
}

double longest_edge(const TriangleMesh &m) {
  double longest = 0.0;
  for (const auto &t : m.triangles)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (m.vertices_m[t[(k + 1) % 3]] - m.vertices_m[t[k]]).norm());
  return longest;
}

struct ToolCase {
  const char *name;
  ToolSpec spec;
};

// The soil-lab tools at their default faceting, and subdivided by --max-edge.
std::vector<ToolCase> tool_cases() {
  return {
      {"bevameter plate-rect", plate_rect(0.3, 0.2, 0.01)},
      {"plate-rect fine", with_max_edge(plate_rect(0.3, 0.2, 0.01), 0.01)},
      {"bevameter plate-disc", plate_disc(0.1, 0.01)},
      {"plate-disc fine", with_max_edge(plate_disc(0.1, 0.01), 0.01)},
      {"plate-disc 30 segments", plate_disc(0.05, 0.005, 30)},
      {"shear-box frame", frame(0.1, 0.1, 0.01, 0.05)},
      {"frame oblong fine", with_max_edge(frame(0.3, 0.1, 0.02, 0.04), 0.015)},
      {"shear ring", ring(0.05, 0.07, 0.02)},
      {"repose cylinder fine", with_max_edge(ring(0.05, 0.055, 0.1), 0.005)},
      {"ring 10 segments", ring(0.01, 0.02, 0.01, 10)},
  };
}

} // namespace

TEST(ToolMesh, EveryToolIsClosedOutwardAndMatchesTheAnalyticSolid) {
  for (const auto &c : tool_cases()) {
    SCOPED_TRACE(c.name);
    const ToolSpec &s = c.spec;
    const GeneratedSolid g = generate_tool(s, 7850.0); // throws if check_mesh fails
    const auto report = wheelsim::geometry::check_mesh(g.mesh);
    EXPECT_TRUE(report.ok());
    EXPECT_TRUE(report.closed());
    EXPECT_TRUE(report.consistently_oriented());
    EXPECT_EQ(report.nonmanifold_edges, 0);
    EXPECT_TRUE(report.degenerate_triangles.empty());
    EXPECT_TRUE(report.warnings.empty());
    EXPECT_GT(report.signed_volume_m3, 0.0); // outward

    // Volume: exact for the polyhedron; boxes and frames are exact, round tools are within 0.5 %
    // of the round solid (0.13 % at the default chord error).
    const double ideal = ideal_volume_m3(s);
    const double err_polygon = std::abs(g.props.volume_m3 / polygon_volume(s) - 1.0);
    const double err_ideal = std::abs(g.props.volume_m3 / ideal - 1.0);
    EXPECT_LT(err_polygon, 1e-12);
    if (!s.round()) {
      EXPECT_LT(err_ideal, 1e-12);
    } else if (s.segments == 0) {
      EXPECT_LT(err_ideal, 0.005);
    }

    // Bounding box centred at the origin; exact unless a round tool has segments that are not a
    // multiple of 4 (given SEGMENTS), whose box is within the chord error.
    const Eigen::Vector3d half(s.half_x_m(), s.half_y_m(), 0.5 * s.height_m);
    if (!s.round() || segment_count(s) % 4 == 0) {
      EXPECT_LT((report.bbox_max_m - half).norm(), 1e-12 * half.norm());
      EXPECT_LT((report.bbox_min_m + half).norm(), 1e-12 * half.norm());
    } else {
      const double sagitta = s.radius_m * (1.0 - std::cos(M_PI / segment_count(s)));
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(report.bbox_max_m[k], half[k] * (1 + 1e-12));
        EXPECT_GE(report.bbox_max_m[k], half[k] - sagitta);
        EXPECT_GE(report.bbox_min_m[k], -half[k] * (1 + 1e-12));
        EXPECT_LE(report.bbox_min_m[k], -half[k] + sagitta);
      }
    }
    // Centroid at the origin.
    EXPECT_LT(g.props.centroid_m.norm(), 1e-12 * half.norm());
    if (s.max_edge_m > 0.0 && (!s.round() || s.segments == 0)) {
      EXPECT_LE(longest_edge(g.mesh), std::sqrt(2.0) * s.max_edge_m * (1 + 1e-12));
    }
    std::printf("%-22s %6zu triangles, volume %.9g m^3, vs round solid %+.4f %%, centroid %.2g m\n",
                c.name, g.mesh.triangles.size(), g.props.volume_m3,
                100.0 * (g.props.volume_m3 / ideal - 1.0), g.props.centroid_m.norm());
  }
}

TEST(ToolMesh, InertiaMatchesTheAnalyticSolid) {
  // Box LX x LY x T: I_xx = m (LY^2 + T^2) / 12, ... (exact for the polyhedron).
  {
    const ToolSpec s = plate_rect(0.3, 0.2, 0.01);
    const auto g = generate_tool(s, 7850.0);
    const double m = 7850.0 * 0.3 * 0.2 * 0.01;
    const auto &I = g.props.inertia_about_centroid_kg_m2;
    EXPECT_NEAR(I(0, 0), m * (0.2 * 0.2 + 0.01 * 0.01) / 12.0, 1e-12 * I(0, 0));
    EXPECT_NEAR(I(1, 1), m * (0.3 * 0.3 + 0.01 * 0.01) / 12.0, 1e-12 * I(1, 1));
    EXPECT_NEAR(I(2, 2), m * (0.3 * 0.3 + 0.2 * 0.2) / 12.0, 1e-12 * I(2, 2));
  }
  // Hollow cylinder: I_zz = m (RI^2 + RO^2) / 2, I_xx = m (3 (RI^2 + RO^2) + H^2) / 12 with the
  // mesh's own mass; the polygon's second moment is lower by about the same relative amount as
  // its area, so compare within 0.5 %.
  {
    const ToolSpec s = ring(0.05, 0.07, 0.02);
    const auto g = generate_tool(s, 7850.0);
    const double m = g.props.mass_kg, r2 = 0.05 * 0.05 + 0.07 * 0.07;
    const auto &I = g.props.inertia_about_centroid_kg_m2;
    const double err_z = std::abs(I(2, 2) / (0.5 * m * r2) - 1.0);
    const double err_x = std::abs(I(0, 0) / (m * (3.0 * r2 + 0.02 * 0.02) / 12.0) - 1.0);
    std::printf("ring inertia relative errors: I_zz %.3g, I_xx %.3g\n", err_z, err_x);
    EXPECT_LT(err_z, 0.005);
    EXPECT_LT(err_x, 0.005);
    EXPECT_NEAR(I(0, 0), I(1, 1), 1e-9 * I(0, 0));
  }
}

TEST(ToolMesh, SegmentsFollowTheChordErrorRule) {
  EXPECT_EQ(segments_for_chord_error(kDefaultChordError), 72);
  for (double f : {1e-6, 1e-4, 5e-4, 1e-3, 3e-3, 1e-2, 0.05}) {
    const int n = segments_for_chord_error(f);
    EXPECT_EQ(n % 4, 0) << f;
    EXPECT_GE(n, kMinSegments) << f;
    EXPECT_LE(1.0 - std::cos(M_PI / n), f) << f; // the rule holds
    if (n > kMinSegments) {
      EXPECT_GT(1.0 - std::cos(M_PI / (n - 4)), f) << f; // and is the smallest multiple of 4
    }
  }
  // Given segments are used as they are; --max-edge raises the default ones.
  EXPECT_EQ(segment_count(plate_disc(0.1, 0.01, 30)), 30);
  EXPECT_EQ(segment_count(plate_disc(0.1, 0.01)), 72);
  const ToolSpec fine = with_max_edge(plate_disc(0.1, 0.01), 0.005);
  const int n = segment_count(fine);
  EXPECT_EQ(n % 4, 0);
  EXPECT_LE(2.0 * 0.1 * std::sin(M_PI / n), 0.005);
  // The mesh has exactly that many vertices on the outer circle of the top face.
  const auto g = generate_tool(plate_disc(0.1, 0.01, 30), 1.0);
  int on_rim = 0;
  for (const auto &v : g.mesh.vertices_m)
    on_rim += std::abs(std::hypot(v.x(), v.y()) - 0.1) < 1e-12 && v.z() > 0.0;
  EXPECT_EQ(on_rim, 30);
}

TEST(ToolMesh, BadSizesAreRejectedNamingValueUnitAndRange) {
  struct Case {
    ToolSpec spec;
    std::string message;
  };
  const std::vector<Case> cases{
      {plate_rect(50, 0.2, 0.01), "LX 50 m is implausible for a plate length (expected 0.005–5 "
                                  "m); the generator takes metres: did you mean LX 0.05?"},
      {plate_rect(0.3, 0.2, 1e-6), "T 1e-06 m is implausible for a plate thickness (expected "
                                   "0.0005–1 m); the generator takes metres"},
      {plate_disc(1e-6, 0.01), "R 1e-06 m is implausible for a plate radius (expected 0.005–5 m)"},
      {plate_disc(0.1, 0.01, 4), "SEGMENTS 4: expected 8–100000 segments"},
      {frame(0.1, 0.1, 0.0, 0.05), "WALL 0 m: the wall thickness must be > 0 m"},
      {frame(0.1, 50, 0.01, 0.05), "LY 50 m is implausible for the hole width of a frame"},
      {frame(0.1, 0.1, 0.01, 50), "H 50 m is implausible for a frame height (expected 0.001–5 m)"},
      {ring(0.06, 0.05, 0.1), "RI 0.06 m >= RO 0.05 m: the hole (inner radius RI) must be "
                              "smaller than the body (outer radius RO)"},
      {ring(0.05, 0.05, 0.1), "RI 0.05 m >= RO 0.05 m"},
      {ring(0.05, 0.0501, 0.1), "the ring wall must be at least 0.0005 m thick"},
      {ring(0.05, 50, 0.1), "RO 50 m is implausible for the outer radius of a ring"},
      {ring(-0.01, 0.05, 0.1), "RI -0.01 m: the inner radius must be > 0 m"},
      {with_max_edge(plate_rect(0.3, 0.2, 0.01), 1e-5), "triangles (at most 1e+07)"},
  };
  for (const auto &c : cases) {
    try {
      build_tool_mesh(c.spec);
      ADD_FAILURE() << "accepted: " << c.message;
    } catch (const ToolSpecError &e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
          << "expected '" << c.message << "' in: " << e.what();
    }
  }
}

TEST(ToolMesh, FixContactIndexSeesTheOutwardFaces) {
  // What fix wheel/cosim does with the mesh: a grain under the bevameter plate touches its bottom
  // face once, pushed down (-z); a grain in the bore of the shear ring touches the inner wall,
  // pushed towards the axis.
  using wheelsim::geometry::SphereContactIndex;
  using wheelsim::geometry::SurfaceContact;
  std::vector<SurfaceContact> contacts;
  const SphereContactIndex plate(generate_tool(plate_rect(0.3, 0.2, 0.01), 1.0).mesh);
  ASSERT_EQ(plate.find_contacts(Eigen::Vector3d(0.01, 0.02, -0.014), 0.01, contacts), 1);
  EXPECT_NEAR(contacts[0].normal.z(), -1.0, 1e-12);
  EXPECT_NEAR(contacts[0].overlap_m, 0.001, 1e-12);
  contacts.clear();
  // Mid-facet of the 72-gon bore (at the vertex lines a grain touches both neighbouring facets
  // of the concave wall: docs/tool-mesh.md, "Contact with the fix").
  const SphereContactIndex bore(generate_tool(ring(0.05, 0.055, 0.1), 1.0).mesh);
  const double half_step = M_PI / 72.0, apothem = 0.05 * std::cos(half_step);
  const Eigen::Vector3d direction(std::cos(half_step), std::sin(half_step), 0.0);
  ASSERT_EQ(bore.find_contacts(0.042 * direction, 0.01, contacts), 1);
  EXPECT_NEAR(contacts[0].normal.dot(direction), -1.0, 1e-9);
  EXPECT_NEAR(contacts[0].overlap_m, 0.01 - (apothem - 0.042), 1e-9);
}
