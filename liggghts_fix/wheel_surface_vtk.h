// The wheel surface as a legacy VTK file (POLYDATA, ASCII) for ParaView, with the pose applied
// and per-triangle cell data, to view beside LIGGGHTS' `dump custom/vtk` particles.
#ifndef WHEELSIM_WHEEL_SURFACE_VTK_H
#define WHEELSIM_WHEEL_SURFACE_VTK_H

#include "wheel_motion.h"
#include "wheelsim/geometry/triangle_mesh.h"

#include <string>
#include <vector>

namespace wheelsim {

/// Writes `mesh` (wheel frame) moved to `state`'s pose (world frame, m) to `path`, with cell
/// data `contact_pressure` [Pa] (one value per triangle) and `contact_count` (contacts counted
/// per triangle over the averaging window). Returns false if the file cannot be written.
bool write_wheel_surface_vtk(const std::string &path, const geometry::TriangleMesh &mesh,
                             const WheelState &state, const std::vector<double> &pressure_Pa,
                             const std::vector<double> &contact_count, long step, double time_s);

} // namespace wheelsim

#endif
