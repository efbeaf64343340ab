// Unit tests of fix wheel/cosim's plain C++ parts: pose integration (as the fix uses it; the
// function itself is tested in tests/pose), prescribed motion, contact history slots, the
// wheel-surface VTK writer and its ParaView collection.
#include "contact_slots.h"
#include "prescribed_motion.h"
#include "wheel_motion.h"
#include "wheel_surface_vtk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

using Eigen::Vector3d;
using namespace wheelsim;

TEST(AdvancePose, ConstantTwistMatchesTheClosedForm) {
  // n steps of constant ω about +y equal one rotation by ω t (what fix move/mesh rotate does).
  WheelPose s;
  s.p_WB_W = Vector3d(1, 2, 3);
  const Vector3d v(0.1, 0, -0.02), w(0, 2.0, 0);
  s.v_WB_W = v;
  s.w_WB_W = w;
  const double dt = 1e-4;
  const int n = 10000;
  for (int i = 0; i < n; ++i)
    s = integrate_pose(s, dt);
  const double t = n * dt;
  // 1e4 additions at coordinates ~3 m: round-off ~ n * eps * 3 m ~ 1e-11 m
  EXPECT_NEAR((s.p_WB_W - (Vector3d(1, 2, 3) + v * t)).norm(), 0.0, 1e-10);
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(2.0 * t, Vector3d::UnitY()));
  EXPECT_NEAR(s.q_WB.angularDistance(expected), 0.0, 1e-10);
  // A wheel point at the top moves forward (+x) for ω along +y.
  const Vector3d top(0, 0, 0.5);
  EXPECT_GT(s.velocity_at(s.p_WB_W + top).x(), v.x());
}

TEST(PrescribedMotion, EvaluatesItsComponentsEveryStep) {
  double speed = 0.0;
  PrescribedMotion m({[&] { return speed; }, [] { return 0.0; }, [] { return 0.0; }},
                     {[] { return 0.0; }, [] { return 1.0; }, [] { return 0.0; }}, "test");
  WheelPose s;
  speed = 1.0;
  s = m.next_state(s, 1, 0.5);
  speed = 3.0;
  s = m.next_state(s, 2, 0.5);
  EXPECT_DOUBLE_EQ(s.p_WB_W.x(), 0.5 + 1.5);
  EXPECT_DOUBLE_EQ(s.v_WB_W.x(), 3.0);
  EXPECT_DOUBLE_EQ(s.w_WB_W.y(), 1.0);
}

namespace {
SlotQuery query(std::int64_t key, double x) { return {key, Vector3d(x, 0, 0)}; }
} // namespace

TEST(ContactSlots, SameFeatureKeepsItsHistory) {
  ContactSlot slots[3];
  clear_contact_slots(slots, 3);
  int slot_of[2];
  SlotQuery q[2] = {query(7, 0.0), query(9, 0.01)};
  match_contact_slots(slots, 3, q, 2, 0.002, true, slot_of);
  ASSERT_GE(slot_of[0], 0);
  ASSERT_GE(slot_of[1], 0);
  EXPECT_NE(slot_of[0], slot_of[1]);
  slots[slot_of[0]].history.shear[0] = 1.5;
  slots[slot_of[1]].history.shear[0] = -2.5;
  SlotQuery again[2] = {query(9, 0.01), query(7, 0.0)}; // other order
  int slot_again[2];
  match_contact_slots(slots, 3, again, 2, 0.002, true, slot_again);
  EXPECT_EQ(slots[slot_again[0]].history.shear[0], -2.5);
  EXPECT_EQ(slots[slot_again[1]].history.shear[0], 1.5);
}

TEST(ContactSlots, HistoryFollowsTheContactOntoANeighbouringFeature) {
  ContactSlot slots[2];
  clear_contact_slots(slots, 2);
  int slot_of[1];
  SlotQuery q[1] = {query(100, 0.0)};
  match_contact_slots(slots, 2, q, 1, 0.002, true, slot_of);
  slots[slot_of[0]].history.shear[1] = 4.0;
  SlotQuery moved[1] = {query(101, 0.0015)}; // next triangle, 1.5 mm on: within the hand-over
  match_contact_slots(slots, 2, moved, 1, 0.002, true, slot_of);
  EXPECT_EQ(slots[slot_of[0]].history.shear[1], 4.0);
  EXPECT_EQ(static_cast<std::int64_t>(slots[slot_of[0]].key), 101);
  SlotQuery far[1] = {query(300, 0.05)}; // a different place: fresh history
  match_contact_slots(slots, 2, far, 1, 0.002, true, slot_of);
  EXPECT_EQ(slots[slot_of[0]].history.shear[1], 0.0);
}

TEST(ContactSlots, EndedContactsFreeTheirSlotsAndOverflowIsReported) {
  ContactSlot slots[2];
  clear_contact_slots(slots, 2);
  int slot_of[3];
  SlotQuery three[3] = {query(1, 0.0), query(2, 0.1), query(3, 0.2)};
  match_contact_slots(slots, 2, three, 3, 0.002, true, slot_of);
  int without = 0;
  for (int j = 0; j < 3; ++j)
    without += slot_of[j] < 0;
  EXPECT_EQ(without, 1);
  SlotQuery none[1] = {query(50, 1.0)};
  match_contact_slots(slots, 2, none, 1, 0.002, true, slot_of);
  int occupied = 0;
  for (const auto &s : slots)
    occupied += s.key >= 0;
  EXPECT_EQ(occupied, 1);
}

TEST(ContactSlots, SetupDoesNotChangeTheSlots) {
  ContactSlot slots[2];
  clear_contact_slots(slots, 2);
  int slot_of[1];
  SlotQuery q[1] = {query(5, 0.0)};
  match_contact_slots(slots, 2, q, 1, 0.002, false, slot_of);
  EXPECT_EQ(slot_of[0], -1);
  EXPECT_LT(slots[0].key, 0);
  EXPECT_LT(slots[1].key, 0);
}

TEST(WheelSurfaceVtk, WritesThePosedMeshAndCellData) {
  geometry::TriangleMesh mesh;
  mesh.vertices_m = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  WheelPose s;
  s.p_WB_W = Vector3d(10, 0, 0);
  s.q_WB = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ());
  const std::string path = ::testing::TempDir() + "wheel_surface_test.vtk";
  ASSERT_TRUE(write_wheel_surface_vtk(path, mesh, s, {1, 2, 3, 4}, {0, 1, 0, 2}, 42, 0.5));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string vtk = text.str();
  EXPECT_NE(vtk.find("POINTS 4 double"), std::string::npos);
  EXPECT_NE(vtk.find("POLYGONS 4 16"), std::string::npos);
  EXPECT_NE(vtk.find("SCALARS contact_pressure double 1"), std::string::npos);
  // vertex (1,0,0) rotated 90° about z and shifted: (10, 1, 0)
  EXPECT_NE(vtk.find("\n10 1 0\n"), std::string::npos) << vtk;
  std::remove(path.c_str());
  EXPECT_FALSE(write_wheel_surface_vtk("/nonexistent-dir/x.vtk", mesh, s, {}, {}, 0, 0));
}

namespace {
std::string read_text(const std::string &path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}
bool exists(const std::string &path) { return std::ifstream(path).good(); }
} // namespace

TEST(PvdSeries, ListsEveryFileWithItsTimeAndRewritesAtomically) {
  const std::string prefix = ::testing::TempDir() + "pvd_series_test";
  std::remove((prefix + ".pvd").c_str());
  PvdSeries series(prefix);
  EXPECT_EQ(series.vtk_path(200), prefix + "_200.vtk");
  const double dt = 0.25;                  // [s], a binary fraction: times print exactly
  for (long step : {0L, 100L, 200L, 200L}) // 200 twice: a run's setup repeats the last step
    ASSERT_TRUE(series.add(step, step * dt));
  const std::string pvd = read_text(prefix + ".pvd");
  EXPECT_NE(pvd.find("<VTKFile type=\"Collection\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("timestep=\"25\" group=\"\" part=\"0\" file=\"pvd_series_test_100.vtk\""),
            std::string::npos)
      << pvd;
  std::size_t datasets = 0;
  for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos;
       at = pvd.find("<DataSet", at + 1))
    ++datasets;
  EXPECT_EQ(datasets, 3u) << pvd;
  EXPECT_FALSE(exists(prefix + ".pvd.tmp")); // renamed, not left behind

  // a run continued from step 100 keeps the earlier entries, drops the old run's later ones
  PvdSeries continued(prefix);
  ASSERT_TRUE(continued.add(100, 0.5));
  ASSERT_EQ(continued.entries().size(), 2u);
  EXPECT_EQ(continued.entries()[0].step, 0);
  EXPECT_EQ(continued.entries()[1].step, 100);
  EXPECT_DOUBLE_EQ(continued.entries()[1].time_s, 0.5);
  std::remove((prefix + ".pvd").c_str());

  // an unwritable folder: false, no temporary file
  PvdSeries nowhere("/nonexistent-dir/wheel");
  EXPECT_FALSE(nowhere.add(0, 0.0));
}
