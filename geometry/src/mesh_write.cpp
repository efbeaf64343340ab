#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

#include <Eigen/Geometry>

#include "wheelsim/geometry/mesh_error.h"
#include "wheelsim/geometry/mesh_io.h"

namespace wheelsim::geometry {
namespace {

struct FileCloser {
  void operator()(std::FILE *f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_for_writing(const std::string &path, const char *mode) {
  File f(std::fopen(path.c_str(), mode));
  if (!f) {
    throw MeshError(path + ": cannot open for writing: " + std::strerror(errno));
  }
  return f;
}

void finish(File &f, const std::string &path) {
  const bool failed = std::ferror(f.get()) != 0;
  if (std::fclose(f.release()) != 0 || failed) {
    throw MeshError(path + ": write failed");
  }
}

Eigen::Vector3d unit_normal(const TriangleMesh &mesh, const std::array<int, 3> &t) {
  const Eigen::Vector3d &a = mesh.vertices_m[t[0]];
  const Eigen::Vector3d n = (mesh.vertices_m[t[1]] - a).cross(mesh.vertices_m[t[2]] - a);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

} // namespace

void write_obj(const TriangleMesh &mesh, const std::string &path) {
  File f = open_for_writing(path, "w");
  std::fprintf(f.get(), "# wheelsim triangle mesh, units: m\n");
  for (const auto &v : mesh.vertices_m) {
    std::fprintf(f.get(), "v %.17g %.17g %.17g\n", v.x(), v.y(), v.z());
  }
  for (const auto &t : mesh.triangles) {
    std::fprintf(f.get(), "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
  }
  finish(f, path);
}

void write_stl(const TriangleMesh &mesh, const std::string &path, StlEncoding encoding) {
  if (encoding == StlEncoding::ascii) {
    File f = open_for_writing(path, "w");
    std::fprintf(f.get(), "solid wheelsim\n");
    for (const auto &t : mesh.triangles) {
      const Eigen::Vector3d n = unit_normal(mesh, t);
      std::fprintf(f.get(), "facet normal %.9g %.9g %.9g\n outer loop\n", n.x(), n.y(), n.z());
      for (int i : t) {
        const Eigen::Vector3d &v = mesh.vertices_m[i];
        std::fprintf(f.get(), "  vertex %.17g %.17g %.17g\n", v.x(), v.y(), v.z());
      }
      std::fprintf(f.get(), " endloop\nendfacet\n");
    }
    std::fprintf(f.get(), "endsolid wheelsim\n");
    finish(f, path);
    return;
  }
  File f = open_for_writing(path, "wb");
  char header[80] = {};
  std::snprintf(header, sizeof header, "wheelsim binary STL, units: m");
  std::fwrite(header, 1, sizeof header, f.get());
  const std::uint32_t count = static_cast<std::uint32_t>(mesh.triangles.size());
  std::fwrite(&count, sizeof count, 1, f.get()); // STL is little-endian, as is x86-64
  for (const auto &t : mesh.triangles) {
    float record[12];
    const Eigen::Vector3d n = unit_normal(mesh, t);
    for (int k = 0; k < 3; ++k) {
      record[k] = static_cast<float>(n[k]);
      for (int v = 0; v < 3; ++v) {
        record[3 + 3 * v + k] = static_cast<float>(mesh.vertices_m[t[v]][k]);
      }
    }
    const std::uint16_t attributes = 0;
    std::fwrite(record, sizeof record, 1, f.get());
    std::fwrite(&attributes, sizeof attributes, 1, f.get());
  }
  finish(f, path);
}

void write_ply(const TriangleMesh &mesh, const std::string &path) {
  File f = open_for_writing(path, "w");
  std::fprintf(f.get(),
               "ply\nformat ascii 1.0\ncomment wheelsim triangle mesh, units: m\n"
               "element vertex %zu\nproperty double x\nproperty double y\nproperty double z\n"
               "element face %zu\nproperty list uchar int vertex_indices\nend_header\n",
               mesh.vertices_m.size(), mesh.triangles.size());
  for (const auto &v : mesh.vertices_m) {
    std::fprintf(f.get(), "%.17g %.17g %.17g\n", v.x(), v.y(), v.z());
  }
  for (const auto &t : mesh.triangles) {
    std::fprintf(f.get(), "3 %d %d %d\n", t[0], t[1], t[2]);
  }
  finish(f, path);
}

void write_mesh(const TriangleMesh &mesh, const std::string &path) {
  auto ends_with = [&](const char *ext) {
    const std::size_t n = std::strlen(ext);
    if (path.size() < n)
      return false;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::tolower(static_cast<unsigned char>(path[path.size() - n + i])) != ext[i])
        return false;
    }
    return true;
  };
  if (ends_with(".obj")) {
    write_obj(mesh, path);
  } else if (ends_with(".stl")) {
    write_stl(mesh, path);
  } else if (ends_with(".ply")) {
    write_ply(mesh, path);
  } else {
    throw MeshError(path + ": unknown mesh extension (expected .obj, .stl or .ply)");
  }
}

} // namespace wheelsim::geometry
