// Merges coincident vertices into one index (builds an indexed mesh from a triangle soup).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace wheelsim::geometry {

/// Gives each distinct position one index.
///
/// With `tolerance_m == 0` positions are merged only when bit-for-bit equal (after turning -0.0
/// into 0.0); this is right for files that store a shared vertex once per triangle (STL), since
/// every copy then has the same digits. With `tolerance_m > 0` positions are keyed by
/// round(x / tolerance_m) per coordinate: two points closer than the tolerance usually merge, but
/// may not when they straddle a cell boundary, so use it only to clean up, never to rely on.
class VertexWelder {
public:
  explicit VertexWelder(double tolerance_m = 0.0);

  /// Index of `p_m` [m] in `vertices()`, adding it if new.
  int index_of(const Eigen::Vector3d &p_m);

  const std::vector<Eigen::Vector3d> &vertices() const { return vertices_; }
  std::vector<Eigen::Vector3d> take_vertices() { return std::move(vertices_); }

private:
  struct Key {
    std::int64_t k[3];
    bool operator==(const Key &o) const {
      return k[0] == o.k[0] && k[1] == o.k[1] && k[2] == o.k[2];
    }
  };
  struct KeyHash {
    std::size_t operator()(const Key &key) const;
  };
  Key key_of(const Eigen::Vector3d &p) const;

  double tolerance_m_;
  std::unordered_map<Key, int, KeyHash> index_;
  std::vector<Eigen::Vector3d> vertices_;
};

} // namespace wheelsim::geometry
