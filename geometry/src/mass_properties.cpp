#include "wheelsim/geometry/mass_properties.h"

#include <sstream>

#include <Eigen/LU>

#include "wheelsim/geometry/mesh_error.h"

namespace wheelsim::geometry {

MassProperties mass_properties(const TriangleMesh &mesh, double density_kg_m3) {
  if (!(density_kg_m3 > 0.0)) {
    std::ostringstream os;
    os << "density must be > 0 kg/m^3, got " << density_kg_m3;
    throw MeshError(os.str());
  }
  if (mesh.triangles.empty()) {
    throw MeshError("mass properties of an empty mesh");
  }
  // Reference point: bounding-box centre, so coordinates are O(size) and round-off stays small.
  Eigen::Vector3d lo = mesh.vertices_m.front(), hi = lo;
  for (const auto &v : mesh.vertices_m) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3d o = 0.5 * (lo + hi);

  // Canonical second-moment matrix of the unit tetrahedron (0, e1, e2, e3):
  // integral of x x^T over it = (1/120) [[2,1,1],[1,2,1],[1,1,2]].
  Eigen::Matrix3d canonical;
  canonical << 2, 1, 1, 1, 2, 1, 1, 1, 2;
  canonical /= 120.0;

  double volume = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero(); // integral of r dV about o
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();   // integral of r r^T dV about o
  for (const auto &t : mesh.triangles) {
    Eigen::Matrix3d a; // columns: the triangle's vertices relative to o
    a.col(0) = mesh.vertices_m[t[0]] - o;
    a.col(1) = mesh.vertices_m[t[1]] - o;
    a.col(2) = mesh.vertices_m[t[2]] - o;
    const double det = a.determinant(); // 6 x signed tetrahedron volume
    volume += det / 6.0;
    first_moment += det / 24.0 * (a.col(0) + a.col(1) + a.col(2));
    covariance += det * a * canonical * a.transpose();
  }
  if (!(volume > 0.0)) {
    std::ostringstream os;
    os << "mass properties need a closed, outward-oriented mesh: signed volume is " << volume
       << " m^3";
    throw MeshError(os.str());
  }

  MassProperties p;
  p.volume_m3 = volume;
  p.density_kg_m3 = density_kg_m3;
  p.mass_kg = density_kg_m3 * volume;
  const Eigen::Vector3d c_rel = first_moment / volume;
  p.centroid_m = o + c_rel;
  // Shift the covariance to the centroid, then I = tr(C) E - C.
  const Eigen::Matrix3d c_centroid =
      density_kg_m3 * (covariance - volume * c_rel * c_rel.transpose());
  p.inertia_about_centroid_kg_m2 = c_centroid.trace() * Eigen::Matrix3d::Identity() - c_centroid;
  return p;
}

Eigen::Matrix3d inertia_about_point(const MassProperties &props, const Eigen::Vector3d &p_m) {
  const Eigen::Vector3d d = p_m - props.centroid_m;
  return props.inertia_about_centroid_kg_m2 +
         props.mass_kg * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

} // namespace wheelsim::geometry
