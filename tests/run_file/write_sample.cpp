// run_file_write_sample: writes run files with known contents for check_run_file.py (h5py).
//   run_file_write_sample sample PATH        a complete file, closed normally
//   run_file_write_sample crash PATH N M     N steps, flush, M more steps, then raise(SIGKILL)
// Contents: see check_run_file.py (the two must agree) and sample_values.h.
#include "sample_values.h"
#include "wheelsim/run_file/run_file.h"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace rf = wheelsim::runfile;

namespace {

const char *const kToml = "# rig config (verbatim)\n[wheel]\nmesh = \"wheel.obj\"\n"
                          "radius = 0.15 # m, \xc2\xb5-wheel\n";

struct Spec {
  const char *name;
  const char *unit;
  int components;
};
const Spec kSeries[] = {{"slip", "1", 1},
                        {"wheel/position", "m", 3},
                        {"wheel/orientation", "1", 4},
                        {"drawbar_pull", "N", 1}};

void write_steps(std::vector<rf::TimeSeries *> &series, std::int64_t first, std::int64_t last) {
  double v[4];
  for (std::int64_t step = first; step <= last; ++step)
    for (auto *s : series) {
      for (int c = 0; c < s->components(); ++c)
        v[c] = sample::value(step, c);
      s->append(step, sample::time_s(step), v);
    }
}

std::vector<rf::TimeSeries *> declare(rf::RunFile &file) {
  std::vector<rf::TimeSeries *> out;
  for (const auto &s : kSeries)
    out.push_back(&file.observable(s.name, s.unit, s.components));
  return out;
}

} // namespace

int main(int argc, char **argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "sample" && argc == 3) {
      rf::RunFile file(argv[2], rf::Creator{"run_file_write_sample", "1.2.3", "abc1234", "Tester"},
                       rf::FlushPolicy{300, 0.0});
      file.set_parameter_text("rig.toml", kToml);
      file.set_parameter("liggghts/arguments", "-in in.wheel -var seed 7");
      file.set_parameter("rig/spring_k", 2.5e4, "N/m");
      file.set_parameter("rig/seed", std::int64_t{42}, "1");
      auto series = declare(file);
      write_steps(series, 1, 2100); // 7 automatic flushes, 3 chunks of 1024
      std::vector<double> grid(4 * 6);
      for (std::size_t i = 0; i < grid.size(); ++i)
        grid[i] = 0.5 * static_cast<double>(i);
      file.write_snapshot("height/002100", 2100, sample::time_s(2100),
                          rf::Grid2D{grid.data(), 4, 6}, "m", {{"dx", 0.25, "m"}});
      file.close();
      return 0;
    }
    if (mode == "crash" && argc == 5) {
      const std::int64_t n = std::atoll(argv[3]), m = std::atoll(argv[4]);
      rf::RunFile file(argv[2], rf::Creator{"run_file_write_sample", "1.2.3", "abc1234"},
                       rf::FlushPolicy{0, 0.0});
      file.set_parameter_text("rig.toml", kToml);
      auto series = declare(file);
      write_steps(series, 1, n);
      file.flush();
      write_steps(series, n + 1, n + m);
      std::raise(SIGKILL);
      return 2; // not reached
    }
  } catch (const rf::RunFileError &e) {
    std::fprintf(stderr, "run_file_write_sample: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "usage: run_file_write_sample sample PATH | crash PATH N M\n");
  return 2;
}
