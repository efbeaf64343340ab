#include <filesystem>
#include <sstream>
#include <system_error>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "wheelsim/geometry/mesh_error.h"
#include "wheelsim/geometry/mesh_io.h"
#include "wheelsim/geometry/vertex_welder.h"

namespace wheelsim::geometry {
namespace {

Eigen::Matrix4d to_eigen(const aiMatrix4x4 &m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return e;
}

struct Collector {
  const aiScene *scene;
  double scale;
  VertexWelder welder;
  std::vector<std::array<int, 3>> triangles;
  int dropped = 0;
  int non_triangles = 0;

  void visit(const aiNode *node, const Eigen::Matrix4d &parent) {
    const Eigen::Matrix4d x = parent * to_eigen(node->mTransformation);
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      add_mesh(scene->mMeshes[node->mMeshes[k]], x);
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) {
      visit(node->mChildren[c], x);
    }
  }

  void add_mesh(const aiMesh *mesh, const Eigen::Matrix4d &x) {
    std::vector<int> index(mesh->mNumVertices);
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D &v = mesh->mVertices[i];
      const Eigen::Vector4d p = x * Eigen::Vector4d(v.x, v.y, v.z, 1.0);
      index[i] = welder.index_of(scale * p.head<3>());
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace &face = mesh->mFaces[f];
      if (face.mNumIndices != 3) {
        non_triangles++; // points and lines: not part of a surface
        continue;
      }
      const std::array<int, 3> t{index[face.mIndices[0]], index[face.mIndices[1]],
                                 index[face.mIndices[2]]};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        dropped++;
        continue;
      }
      triangles.push_back(t);
    }
  }
};

} // namespace

TriangleMesh load_mesh(const std::string &path, const LoadOptions &options, MeshReport *report) {
  if (!(options.scale > 0.0)) {
    std::ostringstream os;
    os << path << ": scale must be > 0 (file units -> m), got " << options.scale;
    throw MeshError(os.str());
  }
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw MeshError(path + ": file not found");
  }
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw MeshError(path + ": not a regular file");
  }
  if (std::filesystem::file_size(path, ec) == 0) {
    throw MeshError(path + ": file is empty");
  }

  Assimp::Importer importer;
  // Triangulate polygons and join vertices that assimp considers identical; nothing that changes
  // winding or normals (no aiProcess_FixInfacingNormals, no aiProcess_GenNormals).
  const aiScene *scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw MeshError(path + ": cannot parse mesh file: " + importer.GetErrorString());
  }
  if (scene->mNumMeshes == 0) {
    throw MeshError(path + ": file contains no mesh");
  }

  Collector c{scene, options.scale, VertexWelder(options.merge_tolerance_m), {}, 0, 0};
  c.visit(scene->mRootNode, Eigen::Matrix4d::Identity());
  if (c.triangles.empty()) {
    throw MeshError(path + ": file contains no triangles");
  }

  TriangleMesh mesh;
  mesh.vertices_m = c.welder.take_vertices();
  mesh.triangles = std::move(c.triangles);

  MeshReport r = check_mesh(mesh);
  if (c.dropped > 0) {
    r.warnings.push_back(std::to_string(c.dropped) +
                         " degenerate triangle(s) with repeated vertices dropped while loading");
  }
  if (c.non_triangles > 0) {
    r.warnings.push_back(std::to_string(c.non_triangles) + " point/line primitive(s) ignored");
  }
  if (report != nullptr) {
    *report = r;
  }
  if (options.validate && !r.ok()) {
    std::string message = path + ": " + r.errors.front();
    for (std::size_t i = 1; i < r.errors.size(); ++i) {
      message += "; " + r.errors[i];
    }
    throw MeshError(message);
  }
  return mesh;
}

} // namespace wheelsim::geometry
