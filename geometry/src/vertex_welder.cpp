#include "wheelsim/geometry/vertex_welder.h"

#include <cmath>
#include <cstring>

#include "wheelsim/geometry/mesh_error.h"

namespace wheelsim::geometry {

VertexWelder::VertexWelder(double tolerance_m) : tolerance_m_(tolerance_m) {
  if (!(tolerance_m >= 0.0)) {
    throw MeshError("vertex merge tolerance must be >= 0 m, got " + std::to_string(tolerance_m));
  }
}

std::size_t VertexWelder::KeyHash::operator()(const Key &key) const {
  std::uint64_t h = 1469598103934665603ull;
  for (std::int64_t v : key.k) {
    h ^= static_cast<std::uint64_t>(v) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  }
  return static_cast<std::size_t>(h);
}

VertexWelder::Key VertexWelder::key_of(const Eigen::Vector3d &p) const {
  Key key{};
  for (int i = 0; i < 3; ++i) {
    if (tolerance_m_ > 0.0) {
      key.k[i] = static_cast<std::int64_t>(std::llround(p[i] / tolerance_m_));
    } else {
      const double v = p[i] == 0.0 ? 0.0 : p[i]; // -0.0 and 0.0 are the same point
      std::memcpy(&key.k[i], &v, sizeof v);
    }
  }
  return key;
}

int VertexWelder::index_of(const Eigen::Vector3d &p_m) {
  const auto [it, inserted] = index_.try_emplace(key_of(p_m), static_cast<int>(vertices_.size()));
  if (inserted) {
    vertices_.push_back(p_m);
  }
  return it->second;
}

} // namespace wheelsim::geometry
