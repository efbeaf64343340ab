#include "wheelsim/geometry/mesh_error.h"

namespace wheelsim::geometry {

MeshError::MeshError(const std::string &message) : std::runtime_error(message) {}

} // namespace wheelsim::geometry
