// Reading (OBJ, STL ascii/binary, PLY — through assimp) and writing (OBJ, STL, PLY) of triangle
// meshes.
#pragma once

#include <string>

#include "wheelsim/geometry/mesh_check.h"
#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::geometry {

struct LoadOptions {
  /// File units -> metres: every coordinate is multiplied by this (e.g. 0.001 for millimetres).
  double scale = 1.0;
  /// Run check_mesh on the result and throw MeshError on any error (open, inconsistently
  /// oriented, inside out, implausible size). Degenerate triangles are only warnings.
  bool validate = true;
  /// Vertices closer than this [m, after scaling] are merged; 0 merges only exactly equal
  /// positions (right for files written by the generator and for STL). See VertexWelder.
  double merge_tolerance_m = 0.0;
};

/// Loads an OBJ, STL (ascii or binary) or PLY file (any format assimp reads) as one indexed mesh
/// in metres. All meshes of all nodes are concatenated with their node transforms applied.
/// assimp post-processing: triangulation only; normals and winding are taken as stored (never
/// "fixed"), coincident vertices are merged here by position (assimp would keep STL corners apart
/// because their face normals differ). Triangles that collapse to repeated indices after merging
/// are dropped and counted as degenerate warnings.
///
/// Note: Debian's assimp stores coordinates in single precision (float), so loaded coordinates
/// carry a relative round-off of about 6e-8 whatever the file's digits.
///
/// Throws MeshError naming `path` and the problem: missing or unreadable file, empty file,
/// unparseable file, a vertex with a NaN or infinite coordinate (also without `validate`: its
/// 1-based number and line among the vertex records of a text OBJ, STL or PLY file; in a binary
/// file its number in assimp's reading order), no triangles, and (with `validate`) every error of
/// check_mesh.
/// If `report` is non-null it receives the check_mesh report (warnings included), also when
/// `validate` is false.
TriangleMesh load_mesh(const std::string &path, const LoadOptions &options = {},
                       MeshReport *report = nullptr);

/// Wavefront OBJ: `v x y z` [m] with 17 significant digits, `f a b c` (1-based).
void write_obj(const TriangleMesh &mesh, const std::string &path);

enum class StlEncoding { ascii, binary };

/// STL with per-facet normals computed from the winding. Default ascii: stock LIGGGHTS
/// (fix mesh/surface) reads only ascii STL, and the text keeps 17 significant digits. Binary STL
/// stores float32 (about 7 digits). STL repeats each vertex per facet; load_mesh re-merges them.
void write_stl(const TriangleMesh &mesh, const std::string &path,
               StlEncoding encoding = StlEncoding::ascii);

/// ASCII PLY: `property double x/y/z` [m], `property list uchar int vertex_indices`.
void write_ply(const TriangleMesh &mesh, const std::string &path);

/// Writes by extension: .obj, .stl (ascii) or .ply; throws MeshError for anything else.
void write_mesh(const TriangleMesh &mesh, const std::string &path);

} // namespace wheelsim::geometry
