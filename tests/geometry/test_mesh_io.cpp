#include <fstream>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "test_meshes_util.h"
#include "wheel_builder.h"
#include "wheelsim/geometry/mesh_error.h"
#include "wheelsim/geometry/mesh_io.h"

using namespace wheelsim::geometry;
namespace fs = std::filesystem;

namespace {

// The small combined-lug test wheel of the catalogue.
TriangleMesh small_wheel() {
  wheelsim::meshes::WheelSpec s;
  s.diameter_m = 0.20;
  s.width_m = 0.08;
  s.lug_count = 8;
  s.lug_height_m = 0.010;
  s.lug_width_m = 0.008;
  s.lug_angle_deg = 25.0;
  s.centre_length_m = 0.020;
  s.type = wheelsim::meshes::LugType::combined;
  s.resolution = {0.01, 6.0, 0.01};
  return wheelsim::meshes::build_wheel_mesh(s);
}

// Expects load_mesh(path) to throw a MeshError whose message contains `path` and `problem`.
void expect_load_error(const fs::path &path, const std::string &problem,
                       const LoadOptions &options = {}) {
  try {
    load_mesh(path.string(), options);
    FAIL() << "no error for " << path;
  } catch (const MeshError &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find(problem), std::string::npos) << what;
  }
}

/// Rewrites the text mesh file `path` with the first coordinate of its `n`-th (1-based) vertex
/// record replaced by `value`: OBJ `v` lines, STL `vertex` lines, PLY rows after end_header.
/// Returns that record's 1-based line number.
int set_vertex_coordinate(const fs::path &path, int n, const std::string &value) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  in.close();
  const bool ply = path.extension() == ".ply";
  bool body = !ply;
  int seen = 0, at = -1;
  for (std::size_t i = 0; i < lines.size() && at < 0; ++i) {
    std::istringstream words(lines[i]);
    std::string first;
    words >> first;
    if (!body) {
      body = first == "end_header";
      continue;
    }
    if ((ply || first == "v" || first == "vertex") && ++seen == n) {
      std::string x, rest;
      if (!ply)
        words >> x;
      std::getline(words, rest);
      lines[i] = (ply ? "" : first + " ") + value + rest;
      at = static_cast<int>(i) + 1;
    }
  }
  std::ofstream out(path);
  for (const std::string &line : lines)
    out << line << "\n";
  return at;
}

} // namespace

TEST(MeshIo, ObjStlPlyLoadIdentically) {
  const fs::path dir = test_meshes::temp_dir("io_formats");
  const TriangleMesh wheel = small_wheel();
  write_obj(wheel, (dir / "w.obj").string());
  write_stl(wheel, (dir / "w.stl").string());
  write_stl(wheel, (dir / "wb.stl").string(), StlEncoding::binary);
  write_ply(wheel, (dir / "w.ply").string());

  MeshReport ref_report;
  const TriangleMesh ref = load_mesh((dir / "w.obj").string(), {}, &ref_report);
  ASSERT_TRUE(ref_report.ok());
  EXPECT_EQ(ref.triangles.size(), wheel.triangles.size());
  EXPECT_EQ(ref.vertices_m.size(), wheel.vertices_m.size());
  EXPECT_NEAR(ref_report.signed_volume_m3, signed_volume(wheel), 1e-6 * signed_volume(wheel));

  struct Case {
    const char *file;
    double rel_tol;
  };
  // Text formats round to the same float32 values in assimp; binary STL stores float32 itself.
  for (const Case c : {Case{"w.stl", 1e-9}, Case{"w.ply", 1e-9}, Case{"wb.stl", 1e-9}}) {
    MeshReport r;
    const TriangleMesh m = load_mesh((dir / c.file).string(), {}, &r);
    SCOPED_TRACE(c.file);
    EXPECT_EQ(m.triangles.size(), ref.triangles.size());
    EXPECT_EQ(m.vertices_m.size(), ref.vertices_m.size());
    EXPECT_NEAR(r.signed_volume_m3, ref_report.signed_volume_m3,
                c.rel_tol * ref_report.signed_volume_m3);
    const double size = ref_report.bbox_diagonal_m;
    EXPECT_LT((r.bbox_min_m - ref_report.bbox_min_m).norm(), c.rel_tol * size);
    EXPECT_LT((r.bbox_max_m - ref_report.bbox_max_m).norm(), c.rel_tol * size);
  }
}

TEST(MeshIo, ScaleOption) {
  const fs::path dir = test_meshes::temp_dir("io_scale");
  TriangleMesh mm = test_meshes::box(300, 200, 100); // a box written in millimetres
  write_obj(mm, (dir / "box_mm.obj").string());
  LoadOptions options;
  options.scale = 0.001;
  MeshReport r;
  load_mesh((dir / "box_mm.obj").string(), options, &r);
  EXPECT_TRUE(r.ok());
  EXPECT_NEAR(r.signed_volume_m3, 0.3 * 0.2 * 0.1, 1e-9);
}

TEST(MeshIo, MissingFile) {
  const fs::path dir = test_meshes::temp_dir("io_missing");
  expect_load_error(dir / "nope.stl", "file not found");
}

TEST(MeshIo, EmptyFile) {
  const fs::path dir = test_meshes::temp_dir("io_empty");
  std::ofstream(dir / "empty.stl").close();
  expect_load_error(dir / "empty.stl", "file is empty");
}

TEST(MeshIo, UnparseableFile) {
  const fs::path dir = test_meshes::temp_dir("io_garbage");
  std::ofstream(dir / "garbage.ply") << "this is not a mesh\n";
  expect_load_error(dir / "garbage.ply", "cannot parse mesh file");
}

TEST(MeshIo, OpenMesh) {
  const fs::path dir = test_meshes::temp_dir("io_open");
  TriangleMesh wheel = small_wheel();
  wheel.triangles.erase(wheel.triangles.begin() + 17);
  write_stl(wheel, (dir / "open.stl").string());
  expect_load_error(dir / "open.stl", "mesh is not closed: 3 boundary edges (first at vertex (");
}

TEST(MeshIo, FlippedTriangle) {
  const fs::path dir = test_meshes::temp_dir("io_flipped");
  TriangleMesh wheel = small_wheel();
  std::swap(wheel.triangles[42][1], wheel.triangles[42][2]);
  write_obj(wheel, (dir / "flipped.obj").string());
  expect_load_error(dir / "flipped.obj", "mesh is inconsistently oriented: 3 edges");
}

TEST(MeshIo, InsideOut) {
  const fs::path dir = test_meshes::temp_dir("io_inside_out");
  TriangleMesh wheel = small_wheel();
  for (auto &t : wheel.triangles)
    std::swap(t[1], t[2]);
  write_ply(wheel, (dir / "inverted.ply").string());
  expect_load_error(dir / "inverted.ply", "mesh is inside out");
}

TEST(MeshIo, WheelWrittenInMillimetres) {
  const fs::path dir = test_meshes::temp_dir("io_mm");
  wheelsim::meshes::WheelSpec s;
  s.diameter_m = 1.234;
  s.width_m = 0.479;
  s.smooth = true;
  s.resolution.max_arc_m = 0.05;
  s.resolution.max_width_edge_m = 0.1;
  TriangleMesh wheel = wheelsim::meshes::build_wheel_mesh(s);
  for (auto &v : wheel.vertices_m)
    v *= 1000.0;
  write_stl(wheel, (dir / "wheel_mm.stl").string());
  expect_load_error(dir / "wheel_mm.stl", "looks like millimetres: use scale 0.001");
  LoadOptions options;
  options.scale = 0.001;
  EXPECT_NO_THROW(load_mesh((dir / "wheel_mm.stl").string(), options));
}

TEST(MeshIo, ValidateOffReturnsReport) {
  const fs::path dir = test_meshes::temp_dir("io_novalidate");
  TriangleMesh box = test_meshes::box(1, 1, 1);
  box.triangles.pop_back();
  write_obj(box, (dir / "open.obj").string());
  LoadOptions options;
  options.validate = false;
  MeshReport r;
  const TriangleMesh m = load_mesh((dir / "open.obj").string(), options, &r);
  EXPECT_EQ(m.triangles.size(), 11u);
  EXPECT_FALSE(r.closed());
}

// A NaN or infinite coordinate (a broken export) is named with the file, the vertex's number among
// the file's vertex records and its line, also without validation, instead of a misleading
// "inside out" or "implausible size" from the checks that follow.
TEST(MeshIo, NonFiniteVertexIsNamedWithItsNumberAndLine) {
  const fs::path dir = test_meshes::temp_dir("io_nonfinite");
  const TriangleMesh box = test_meshes::box(1, 1, 1);
  struct Case {
    const char *file;
    int vertex;
    const char *value;
  };
  for (const Case c : {Case{"box.obj", 3, "nan"}, Case{"box.stl", 5, "inf"},
                       Case{"box.ply", 2, "-nan"}, Case{"big.obj", 7, "1e40"}}) {
    SCOPED_TRACE(c.file);
    const fs::path path = dir / c.file;
    write_mesh(box, path.string());
    const int line = set_vertex_coordinate(path, c.vertex, c.value);
    ASSERT_GT(line, 0);
    const std::string where = "vertex " + std::to_string(c.vertex) + " (line " +
                              std::to_string(line) +
                              ") has a coordinate that is not a finite number";
    expect_load_error(path, where);
    LoadOptions unchecked;
    unchecked.validate = false;
    expect_load_error(path, where, unchecked);
  }
}
