// Generating, validating and writing one wheel or tool, and its mass-property summary.
#pragma once

#include <string>
#include <vector>

#include "tool_spec.h"
#include "wheel_spec.h"
#include "wheelsim/geometry/mass_properties.h"
#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::meshes {

/// A generated solid (wheel or tool), validated, with its mass properties.
struct GeneratedSolid {
  geometry::TriangleMesh mesh;
  geometry::MassProperties props;
  std::vector<std::string> warnings; // from check_mesh
};

/// Builds the wheel, validates it with geometry::check_mesh (throws WheelSpecError listing the
/// errors if the generator produced an invalid mesh — a bug, never expected) and computes its
/// mass properties for `density_kg_m3`.
GeneratedSolid generate_wheel(const WheelSpec &spec, double density_kg_m3);

/// Builds the tool, validates it with geometry::check_mesh (throws ToolSpecError listing the
/// errors if the generator produced an invalid mesh — a bug, never expected) and computes its
/// mass properties for `density_kg_m3`.
GeneratedSolid generate_tool(const ToolSpec &spec, double density_kg_m3);

/// Writes `<prefix>.<ext>` for each ext in `formats` ("obj", "stl", "ply"); returns the paths.
std::vector<std::string> write_mesh_files(const geometry::TriangleMesh &mesh,
                                          const std::string &prefix,
                                          const std::vector<std::string> &formats);

/// Writes the summary (parameters, counts, volume, mass, centroid, inertia about the centroid
/// and about the wheel centre) as TOML or JSON, chosen by the extension of `path`.
void write_properties(const std::string &path, const std::string &name, const WheelSpec &spec,
                      const GeneratedSolid &wheel, const std::vector<std::string> &mesh_files);

/// The tool's summary (parameters, segments, counts, volume and ideal volume, mass, centroid,
/// inertia about the centroid and about the origin) as TOML or JSON, chosen by the extension.
void write_properties(const std::string &path, const std::string &name, const ToolSpec &spec,
                      const GeneratedSolid &tool, const std::vector<std::string> &mesh_files);

/// The same summaries as human-readable text (for stdout).
std::string format_properties(const std::string &name, const WheelSpec &spec,
                              const GeneratedSolid &wheel);
std::string format_properties(const std::string &name, const ToolSpec &spec,
                              const GeneratedSolid &tool);

} // namespace wheelsim::meshes
