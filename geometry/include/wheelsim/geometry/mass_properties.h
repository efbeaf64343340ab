// Volume, mass, centroid and inertia tensor of a closed triangle mesh of uniform density.
#pragma once

#include <Eigen/Core>

#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::geometry {

/// Mass properties of a uniform solid, all in the mesh's frame (for wheel meshes: the wheel frame,
/// centre at the origin, axle +y).
struct MassProperties {
  double volume_m3 = 0.0;
  double density_kg_m3 = 0.0;
  double mass_kg = 0.0;
  /// Centre of mass [m] (= centroid of the volume).
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  /// Inertia tensor about the centroid, axes parallel to the mesh frame [kg m^2]:
  /// I = integral of rho (|r|^2 E - r r^T) dV, r measured from the centroid.
  Eigen::Matrix3d inertia_about_centroid_kg_m2 = Eigen::Matrix3d::Zero();
};

/// Mass properties of the solid bounded by `mesh` with uniform `density_kg_m3` (> 0).
/// Divergence theorem on signed tetrahedra (one per triangle, apex at a reference point): the
/// second moments of each tetrahedron are exact, so the result is exact for the polyhedron
/// (to round-off). Requires a closed, outward-oriented mesh; throws MeshError if the volume is not
/// positive or the density not > 0.
MassProperties mass_properties(const TriangleMesh &mesh, double density_kg_m3);

/// Inertia tensor [kg m^2] of `props` about the point `p_m` [m] (parallel-axis theorem):
/// I_p = I_c + m (|d|^2 E - d d^T), d = p - centroid.
Eigen::Matrix3d inertia_about_point(const MassProperties &props, const Eigen::Vector3d &p_m);

} // namespace wheelsim::geometry
