#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
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

/// A vertex with a coordinate that is not a finite number, as assimp read it (file units).
struct NonFiniteVertex {
  long read_index = 0; ///< 0-based, in assimp's reading order over all meshes
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct Collector {
  const aiScene *scene;
  double scale;
  VertexWelder welder;
  std::vector<std::array<int, 3>> triangles;
  int dropped = 0;
  int non_triangles = 0;
  long vertices_read = 0;
  std::optional<NonFiniteVertex> nonfinite; ///< the first one

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
    for (unsigned i = 0; i < mesh->mNumVertices; ++i, ++vertices_read) {
      const aiVector3D &v = mesh->mVertices[i];
      if (!nonfinite && !(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
        nonfinite = NonFiniteVertex{vertices_read, Eigen::Vector3d(v.x, v.y, v.z)};
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

/// A vertex record of a text mesh file: its 1-based number among the file's vertices, its line.
struct VertexRecord {
  long number = 0;
  long line = 0;
};

/// True if `token` is a number that is not finite in single precision (assimp's float): "nan",
/// "inf", "1e40".
bool nonfinite_number(const std::string &token) {
  char *end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  return end != token.c_str() && !std::isfinite(static_cast<float>(v));
}

/// The first vertex record of a text mesh file with a coordinate that is not a finite number:
/// OBJ `v x y z` lines, ASCII STL `vertex x y z` lines, ASCII PLY vertex rows (x, y, z wherever
/// the header puts them). nullopt for binary files, or if no such record is found.
std::optional<VertexRecord> find_nonfinite_vertex_record(const std::string &path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  std::ifstream in(path, std::ios::binary);
  std::string line;
  long line_number = 0, number = 0;
  // PLY: the header says which columns of the vertex rows are x, y, z and how many rows there are.
  std::vector<int> columns = {0, 1, 2};
  long ply_vertices = -1;
  if (ext == ".ply") {
    bool ascii = false, in_vertex = false, first_element = true;
    int property = 0;
    while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
      ++line_number;
      std::istringstream words(line);
      std::string word, a, b, name;
      words >> word;
      if (word == "format") {
        words >> a;
        ascii = a == "ascii";
      } else if (word == "element") {
        words >> a >> b;
        in_vertex = first_element && a == "vertex";
        if (in_vertex)
          ply_vertices = std::atol(b.c_str());
        first_element = false;
      } else if (word == "property" && in_vertex) {
        while (words >> a)
          name = a; // the last word is the property's name
        for (int axis = 0; axis < 3; ++axis)
          if (name == std::string(1, static_cast<char>('x' + axis)))
            columns[axis] = property;
        ++property;
      }
    }
    ++line_number; // end_header
    if (!ascii || ply_vertices < 0)
      return std::nullopt;
  }
  const char *keyword = ext == ".obj" ? "v" : "vertex";
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream words(line);
    std::vector<std::string> tokens;
    for (std::string t; words >> t;)
      tokens.push_back(t);
    std::vector<std::string> xyz;
    if (ext == ".ply") {
      if (number >= ply_vertices)
        return std::nullopt;
      for (int c : columns)
        xyz.push_back(c < static_cast<int>(tokens.size()) ? tokens[c] : "0");
    } else if (!tokens.empty() && tokens[0] == keyword) {
      xyz.assign(tokens.begin() + 1, tokens.begin() + std::min<std::size_t>(tokens.size(), 4));
    } else {
      continue;
    }
    ++number;
    if (std::any_of(xyz.begin(), xyz.end(), nonfinite_number))
      return VertexRecord{number, line_number};
  }
  return std::nullopt;
}

/// "<path>: vertex 100 (line 101) has a coordinate that is not a finite number: ...".
std::string nonfinite_vertex_message(const std::string &path, const NonFiniteVertex &v) {
  std::ostringstream os;
  os << path << ": vertex ";
  if (const auto record = find_nonfinite_vertex_record(path))
    os << record->number << " (line " << record->line << ")";
  else
    os << v.read_index + 1 << " (in assimp's reading order)";
  os << " has a coordinate that is not a finite number: " << format_point(v.position)
     << " in file units; every vertex needs three finite coordinates (fix the export that wrote "
        "the file)";
  return os.str();
}

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
  // Triangulate polygons; nothing that changes winding or normals (no
  // aiProcess_FixInfacingNormals, no aiProcess_GenNormals). Vertices are welded by position below
  // (VertexWelder), not by aiProcess_JoinIdenticalVertices: that step compares every vertex
  // attribute, so on an STL (a normal per facet) it joins almost nothing, and it was most of the
  // load time of a study wheel (wheel-rig --check).
  const aiScene *scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw MeshError(path + ": cannot parse mesh file: " + importer.GetErrorString());
  }
  if (scene->mNumMeshes == 0) {
    throw MeshError(path + ": file contains no mesh");
  }

  Collector c{scene, options.scale, VertexWelder(options.merge_tolerance_m), {}, 0, 0, 0, {}};
  c.visit(scene->mRootNode, Eigen::Matrix4d::Identity());
  if (c.nonfinite) {
    throw MeshError(nonfinite_vertex_message(path, *c.nonfinite));
  }
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
