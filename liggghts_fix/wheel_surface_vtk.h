// The wheel surface as a legacy VTK file (POLYDATA, ASCII) for ParaView, with the pose applied
// and per-triangle cell data, to view beside LIGGGHTS' `dump custom/vtk` particles.
#ifndef WHEELSIM_WHEEL_SURFACE_VTK_H
#define WHEELSIM_WHEEL_SURFACE_VTK_H

#include "wheelsim/geometry/triangle_mesh.h"
#include "wheelsim/pose.h"

#include <string>
#include <vector>

namespace wheelsim {

/// Writes `mesh` (wheel frame) moved to `state`'s pose (world frame, m) to `path`, with cell
/// data `contact_pressure` [Pa] (one value per triangle) and `contact_count` (contacts counted
/// per triangle over the averaging window). Returns false if the file cannot be written.
bool write_wheel_surface_vtk(const std::string &path, const geometry::TriangleMesh &mesh,
                             const WheelPose &state, const std::vector<double> &pressure_Pa,
                             const std::vector<double> &contact_count, long step, double time_s);

/// One file of a ParaView Data collection: the step it belongs to, its simulation time [s] and
/// its name relative to the collection file's folder.
struct PvdEntry {
  long step = 0;
  double time_s = 0.0;
  std::string file;
};

/// Writes the ParaView Data collection `path` (XML, `<DataSet timestep=T file=F/>` per entry, in
/// the given order, times with 17 significant digits) atomically: into `path + ".tmp"`, flushed to
/// disk, then renamed over `path`, so a crash leaves either the old or the new file, never a torn
/// one. Returns false (and removes the temporary file) if it cannot be written.
bool write_pvd(const std::string &path, const std::vector<PvdEntry> &entries);

/// The series `PREFIX_<step>.vtk` of one writer and its collection `PREFIX.pvd` (same folder),
/// rewritten every time a file is added. A collection that already exists when the first file is
/// added keeps its entries of earlier steps (a run continued from a restart extends the series of
/// the run it continues); later ones, left by an older run, are dropped.
class PvdSeries {
public:
  explicit PvdSeries(std::string prefix);
  /// `PREFIX_<step>.vtk`.
  std::string vtk_path(long step) const;
  /// `PREFIX.pvd`.
  const std::string &pvd_path() const { return pvd_path_; }
  /// Lists `vtk_path(step)` at time `time_s` [s] (replacing an entry of the same step) and
  /// rewrites the collection (write_pvd). Returns false if it cannot be written.
  bool add(long step, double time_s);
  const std::vector<PvdEntry> &entries() const { return entries_; }

private:
  void keep_earlier_entries(long step);
  std::string prefix_, pvd_path_, file_stem_; // file_stem_: PREFIX's file name + "_"
  std::vector<PvdEntry> entries_;
  bool started_ = false;
};

} // namespace wheelsim

#endif
