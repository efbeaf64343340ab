// Builds the closed, outward-oriented triangle mesh of a wheel.
#pragma once

#include "wheel_spec.h"
#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::meshes {

/// Builds the wheel of `spec` in the wheel frame (centre at the origin, axle +y, x forward, z up;
/// a point at radius r and angle theta about +y is (r sin theta, y, r cos theta), so theta is
/// measured from +z towards +x and grows under forward rolling).
///
/// The solid is the rim cylinder (radius D0/2 - lh, flat side discs) plus the lugs, extruded
/// radially from their footprints on the lug top (radius D0/2). The result is closed,
/// consistently oriented and outward (checked by the caller with geometry::check_mesh).
/// Throws WheelSpecError for invalid parameters, including lugs that would touch or overlap.
geometry::TriangleMesh build_wheel_mesh(const WheelSpec &spec);

} // namespace wheelsim::meshes
