// Helpers of the SCM tests: wheel meshes built in double precision and the soils of
// TERRAMECHANICS.md §6 (kc, kφ in N units = table × 1000).
#pragma once

#include "wheelsim/geometry/triangle_mesh.h"
#include "wheelsim/scm/soil.h"
#include "wheelsim/scm/soil_file.h"

#include <cmath>

namespace wheelsim::scm::test {

/// Closed cylinder (wheel frame: axle +y, centre at the origin) of radius R [m], width w [m], with
/// `around` flat facets around the rim, `across` strips across it, fan caps; outward normals.
inline geometry::TriangleMesh make_cylinder(double R, double w, int around, int across = 1) {
  geometry::TriangleMesh m;
  auto ring = [&](int k, int i) { return k * around + (i % around); };
  for (int k = 0; k <= across; ++k) {
    const double y = -0.5 * w + w * k / across;
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around;
      m.vertices_m.emplace_back(R * std::cos(a), y, R * std::sin(a));
    }
  }
  const int c0 = static_cast<int>(m.vertices_m.size());
  m.vertices_m.emplace_back(0.0, -0.5 * w, 0.0);
  m.vertices_m.emplace_back(0.0, 0.5 * w, 0.0);
  auto add = [&](int a, int b, int c, const Eigen::Vector3d &outward) {
    const Eigen::Vector3d n =
        (m.vertices_m[b] - m.vertices_m[a]).cross(m.vertices_m[c] - m.vertices_m[a]);
    if (n.dot(outward) >= 0.0)
      m.triangles.push_back({a, b, c});
    else
      m.triangles.push_back({a, c, b});
  };
  for (int k = 0; k < across; ++k)
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * (i + 0.5) / around;
      const Eigen::Vector3d out(std::cos(a), 0.0, std::sin(a));
      add(ring(k, i), ring(k, i + 1), ring(k + 1, i + 1), out);
      add(ring(k, i), ring(k + 1, i + 1), ring(k + 1, i), out);
    }
  for (int i = 0; i < around; ++i) {
    add(c0, ring(0, i), ring(0, i + 1), Eigen::Vector3d(0, -1, 0));
    add(c0 + 1, ring(across, i), ring(across, i + 1), Eigen::Vector3d(0, 1, 0));
  }
  return m;
}

/// Axis-aligned box [m] centred at the origin: a flat plate for pressure–sinkage tests.
inline geometry::TriangleMesh make_box(double lx, double ly, double lz) {
  geometry::TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices_m.emplace_back((k & 1 ? 0.5 : -0.5) * lx, (k & 2 ? 0.5 : -0.5) * ly,
                              (k & 4 ? 0.5 : -0.5) * lz);
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto &f : faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

/// The shipped soil files (inputs/scm_soils), the single source of the soil values.
inline SoilParameters lete_sand() { return load_soil_file(WHEELSIM_SOIL_DIR "/lete_sand.toml"); }
inline SoilParameters dry_sand() { return load_soil_file(WHEELSIM_SOIL_DIR "/dry_sand.toml"); }

} // namespace wheelsim::scm::test
