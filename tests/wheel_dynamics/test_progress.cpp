// wheel-rig's progress line (wheel_dynamics/app/progress.cpp): the steps-per-second rate counts
// only the steps this process ran, so a run resumed from a checkpoint at step N does not report
// N steps in its first interval (it printed "1155 steps/s, ETA 00:01:31" for a point that had
// 50 min left, 2026-11-26); slip, drawbar pull and sinkage are means over the steps since the
// previous line (single steps on DEM soil printed -276, +29 and -1670 N in three lines a minute
// apart, 2026-11-28).
#include "progress.h"
#include "wheelsim/rig/rig_config.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace wheelsim::rig {
namespace {

std::string read_all(std::FILE *f) {
  std::rewind(f);
  std::string text;
  char buf[512];
  while (std::fgets(buf, sizeof(buf), f))
    text += buf;
  return text;
}

TEST(ProgressLine, FirstLineAfterAResumeCountsOnlyItsOwnSteps) {
  const RigSimulation sim(load_rig_config(RIG_EXAMPLE_CONFIG));
  std::FILE *f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressLine line(1e-9, f); // a line at every update
  RigOutputs o;
  o.step = 66903; // the checkpoint's step: the first this process runs
  o.time_s = 2.94;
  line.update(sim, o);
  const std::string text = read_all(f);
  std::fclose(f);
  EXPECT_NE(text.find("t = 2.9400 s"), std::string::npos) << text;
  EXPECT_NE(text.find(", 0 steps/s,"), std::string::npos) << text;
}

TEST(ProgressLine, PrintsTheMeansOverTheStepsSinceThePreviousLine) {
  const RigSimulation sim(load_rig_config(RIG_EXAMPLE_CONFIG));
  std::FILE *f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressLine line(1e9, f); // no line by itself: printed below
  RigOutputs o;
  const double pull_N[] = {-1000.0, 500.0, -2000.0}, sinkage_m[] = {0.30, 0.31, 0.32};
  for (int i = 0; i < 3; ++i) {
    o.step = 100 + i;
    o.slip = 0.1 * (i + 1);
    o.drawbar_pull_N = pull_N[i];
    o.sinkage_m = sinkage_m[i];
    line.update(sim, o);
  }
  line.print(sim, o);
  o.step = 103;
  o.drawbar_pull_N = 40.0;
  line.print(sim, o); // nothing added since: this step's values
  const std::string text = read_all(f);
  std::fclose(f);
  const auto second = text.find('\n') + 1;
  EXPECT_NE(text.find("slip 0.2000, drawbar pull -833.3 N, sinkage 0.31 m"), std::string::npos)
      << text;
  EXPECT_NE(text.find("drawbar pull 40 N", second), std::string::npos) << text;
}

} // namespace
} // namespace wheelsim::rig
