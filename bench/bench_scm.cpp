// bench-scm: cost per step of the SCM grid terrain (wheelsim_scm) with prescribed steady
// kinematics, against Project Chrono's SCMTerrain anchor (smooth wheel, one thread: 2.0 ms/step
// at Δ = 2 cm, 8.8 ms/step at 1 cm). Target: ≤ 0.2 ms/step at 2 cm for the smooth wheel.
//
// For each wheel (smooth_1234, wheel2) and Δ: a quick quasi-static lowering (25 µm per step)
// finds the centre height that carries W = 13.2 kN on LETE sand (TERRAMECHANICS.md §6, Ke 2e8
// Pa/m, R 3e4 Pa s/m), then the wheel rolls at that height at 20 % slip, ω = 1.05 rad/s,
// dt = 5e-4 s; the timed window follows 0.25 s of run-in. A last run rolls the smooth wheel over
// a 20 m track. Prints wall time per step [ms], real-time factor, the ratio to Chrono's anchor
// and the breakdown of ScmTerrain::last_step_timings(). A benchmark, not a test: its numbers
// depend on the machine. Usage: bench-scm [MESH_DIR]
#include "wheelsim/geometry/mesh_io.h"
#include "wheelsim/scm/scm_terrain.h"
#include "wheelsim/scm/soil_file.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

namespace {

using namespace wheelsim;

constexpr double kLoad_N = 13200.0;
constexpr double kOmega = 1.05; // rad/s
constexpr double kSlip = 0.2;
constexpr double kDt = 5e-4; // s

scm::SoilParameters lete_sand() { return scm::load_soil_file(WHEELSIM_SOIL_DIR "/lete_sand.toml"); }

double outer_radius(const geometry::TriangleMesh &m) {
  double r = 0.0;
  for (const auto &v : m.vertices_m)
    r = std::max(r, std::hypot(v.x(), v.z()));
  return r;
}

// Centre height [m] at which the wheel, lowered at 5 cm/s onto fresh soil, carries W.
double height_for_load(const geometry::TriangleMesh &mesh, double R, double delta) {
  scm::ScmSettings s;
  s.grid_spacing_m = delta;
  scm::ScmTerrain t(lete_sand(), s, mesh);
  WheelPose b;
  b.p_WB_W = Eigen::Vector3d(0, 0, R + 1e-3);
  b.v_WB_W = Eigen::Vector3d(0, 0, -0.05);
  for (int k = 0; k < 40000; ++k) {
    if (t.advance(b, kDt).wrench.f_B_W.z() >= kLoad_N)
      return b.p_WB_W.z();
    b.p_WB_W.z() += b.v_WB_W.z() * kDt;
  }
  throw std::runtime_error("load never reached while lowering");
}

struct Result {
  double ms_per_step = 0, raster = 0, law = 0, patches = 0, bulldozing = 0;
  double fz = 0, fx = 0, nodes = 0, triangles = 0;
  std::size_t stored = 0;
};

Result roll(const geometry::TriangleMesh &mesh, double R, double delta, double z_centre,
            double seconds) {
  scm::ScmSettings s;
  s.grid_spacing_m = delta;
  scm::ScmTerrain t(lete_sand(), s, mesh);
  const double v = kOmega * R * (1.0 - kSlip);
  WheelPose b;
  b.v_WB_W = Eigen::Vector3d(v, 0, 0);
  b.w_WB_W = Eigen::Vector3d(0, kOmega, 0);
  const int run_in = static_cast<int>(0.25 / kDt), steps = static_cast<int>(seconds / kDt);
  Result r;
  double wall = 0.0;
  for (int k = 0; k < run_in + steps; ++k) {
    b.p_WB_W = Eigen::Vector3d(v * kDt * k, 0, z_centre);
    b.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(kOmega * kDt * k, Eigen::Vector3d::UnitY()));
    const auto t0 = std::chrono::steady_clock::now();
    const scm::ScmContact c = t.advance(b, kDt);
    const auto t1 = std::chrono::steady_clock::now();
    if (k < run_in)
      continue;
    wall += std::chrono::duration<double, std::milli>(t1 - t0).count();
    const scm::ScmStepTimings &tm = t.last_step_timings();
    r.raster += tm.rasterisation_ms;
    r.law += tm.node_law_ms;
    r.patches += tm.patches_ms;
    r.bulldozing += tm.bulldozing_ms;
    r.fz += c.wrench.f_B_W.z();
    r.fx += c.wrench.f_B_W.x();
    r.nodes += c.contact_nodes;
    r.triangles += tm.triangles_rasterised;
  }
  for (double *x :
       {&r.raster, &r.law, &r.patches, &r.bulldozing, &r.fz, &r.fx, &r.nodes, &r.triangles})
    *x /= steps;
  r.ms_per_step = wall / steps;
  r.stored = t.stored_nodes();
  return r;
}

void print(const char *wheel, double delta, double anchor_ms, double z_sink, const Result &r) {
  std::printf("%-12s %4.0f mm  sinkage %5.1f mm  %7.3f ms/step  RTF %6.1f  ", wheel, delta * 1e3,
              z_sink * 1e3, r.ms_per_step, kDt * 1e3 / r.ms_per_step);
  if (anchor_ms > 0)
    std::printf("vs Chrono %.3f  ", r.ms_per_step / anchor_ms);
  else
    std::printf("vs Chrono   -    ");
  std::printf("[raster %.3f, law %.3f, patches %.3f, bulldozing %.3f ms]  Fz %.0f N  Fx %.0f N  "
              "%.0f nodes  %.0f tris  %zu stored\n",
              r.raster, r.law, r.patches, r.bulldozing, r.fz, r.fx, r.nodes, r.triangles, r.stored);
}

} // namespace

int main(int argc, char **argv) {
  try {
    const std::string dir = argc > 1 ? argv[1] : WHEELSIM_MESH_DIR;
    std::printf("bench-scm: LETE sand, W %.1f kN, slip %.0f %%, omega %.2f rad/s, dt %.0e s, "
                "one thread\n",
                kLoad_N / 1e3, kSlip * 100, kOmega, kDt);
    for (const char *wheel : {"smooth_1234", "wheel2"}) {
      const geometry::TriangleMesh mesh = geometry::load_mesh(dir + "/" + wheel + ".obj");
      const double R = outer_radius(mesh);
      for (double delta : {0.02, 0.01}) {
        const double z = height_for_load(mesh, R, delta);
        const bool smooth = std::string(wheel) == "smooth_1234";
        const double anchor = smooth ? (delta > 0.015 ? 2.0 : 8.8) : 0.0;
        print(wheel, delta, anchor, R - z, roll(mesh, R, delta, z, 1.0));
      }
    }
    const geometry::TriangleMesh mesh = geometry::load_mesh(dir + "/smooth_1234.obj");
    const double R = outer_radius(mesh);
    const double z = height_for_load(mesh, R, 0.02);
    const double track_s = 20.0 / (kOmega * R * (1.0 - kSlip));
    std::printf("long track (20 m):\n");
    print("smooth_1234", 0.02, 2.0, R - z, roll(mesh, R, 0.02, z, track_s));
    return 0;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "bench-scm: %s\n", e.what());
    return 1;
  }
}
