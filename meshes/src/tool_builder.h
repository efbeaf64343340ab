// Builds the closed, outward-oriented triangle mesh of a tool (tool_spec.h).
#pragma once

#include "tool_spec.h"
#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::meshes {

/// Builds the tool of `spec` in its body frame (centred at the origin, z up, metres), after
/// validate(spec) (throws ToolSpecError). Every tool is a plane region extruded along z from
/// -height/2 to +height/2: the region is meshed as convex cells (a rectilinear grid for the
/// plate and the frame, a polar grid for the disc and the ring), the two caps are its cells and
/// the side walls are its boundary edges swept over the z levels. The result is closed and
/// outward (checked by the caller with geometry::check_mesh).
geometry::TriangleMesh build_tool_mesh(const ToolSpec &spec);

} // namespace wheelsim::meshes
