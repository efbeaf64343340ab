// The exception type of the geometry library.
#pragma once

#include <stdexcept>
#include <string>

namespace wheelsim::geometry {

/// Thrown for unreadable or invalid meshes and bad arguments. The message names the file (when
/// there is one) and the problem, e.g.
/// "meshes/x.stl: mesh is not closed: 12 boundary edges (first at vertex (0.1, 0, 0.3) m)".
class MeshError : public std::runtime_error {
public:
  explicit MeshError(const std::string &message);
};

} // namespace wheelsim::geometry
