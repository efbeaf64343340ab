// wong-reece: drawbar pull, torque, sinkage and efficiency of a driven rigid wheel on a soil file
// by the Wong–Reece model, over a list of slips; optionally the stress distribution at one slip.
// Usage and output columns: docs/wong-reece.md.
#include "wheelsim/cli.h"
#include "wheelsim/scm/soil_file.h"
#include "wheelsim/scm/wong_reece.h"

#include "wheelsim_version.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace wheelsim::scm;

constexpr double kRadToDeg = 57.295779513082320876;

/// Bad command-line value: the message names the option, the expected range and the value.
using UsageError = wheelsim::cli::UsageError;

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

void require(bool ok, const char *option, const char *range, double v) {
  if (!ok)
    throw UsageError(std::string(option) + " must be " + range + ", got " + fmt(v));
}

} // namespace

int main(int argc, char **argv) {
  CLI::App app{"wong-reece: driven rigid wheel on soft soil, Wong–Reece model "
               "(docs/wong-reece.md)"};
  std::string soil_path, csv_path, dist_csv_path;
  double radius = 0, width = 0, load = 0;
  std::vector<double> slips = {0.1, 0.2, 0.3, 0.4, 0.5};
  WongReeceOptions opt;
  std::optional<double> dist_slip;
  int dist_points = 91;
  app.add_option("--soil", soil_path, "soil file (TOML, inputs/scm_soils/*.toml)")->required();
  app.add_option("--radius", radius, "wheel radius R [m], > 0")->required();
  app.add_option("--width", width, "wheel width b [m], > 0")->required();
  app.add_option("--load", load, "vertical load W [N], > 0")->required();
  app.add_option("--slips", slips, "slips s in [0, 1], comma separated (default 0.1,...,0.5)")
      ->delimiter(',');
  app.add_option("--c1", opt.c1, "theta_m = (c1 + c2 s) theta_1: c1 in [0, 1) (default 0.43)");
  app.add_option("--c2", opt.c2, "c2 (default 0.32); c1 + c2 s must stay in [0, 1)");
  app.add_option("--rebound", opt.rebound_ratio, "rebound ratio lambda in [0, 1] (default 0)");
  app.add_option("--points", opt.quadrature_points,
                 "tanh-sinh nodes per stress region, >= 9 (default 129)");
  app.add_option("--csv", csv_path, "also write the table to this CSV file (SI units)");
  app.add_option("--distribution", dist_slip, "print sigma, tau and j vs theta at this slip");
  app.add_option("--distribution-points", dist_points,
                 "angles in the distribution, >= 2 (default 91)");
  app.add_option("--distribution-csv", dist_csv_path, "also write the distribution to this CSV");
  wheelsim::cli::setup(app, "wong-reece");
  if (const auto status = wheelsim::cli::parse(app, argc, argv))
    return *status;

  SoilParameters soil;
  WongReeceWheel wheel{radius, width};
  try {
    require(radius > 0 && std::isfinite(radius), "--radius", "> 0 m", radius);
    require(width > 0 && std::isfinite(width), "--width", "> 0 m", width);
    require(load > 0 && std::isfinite(load), "--load", "> 0 N", load);
    if (slips.empty())
      throw UsageError("--slips needs at least one slip in [0, 1]");
    for (double s : slips)
      require(s >= 0 && s <= 1, "--slips: each slip", "in [0, 1] (driven wheel)", s);
    require(opt.c1 >= 0 && opt.c1 < 1, "--c1", "in [0, 1)", opt.c1);
    for (double s : slips)
      require(opt.c1 + opt.c2 * s >= 0 && opt.c1 + opt.c2 * s < 1,
              ("--c2: c1 + c2 s at slip " + fmt(s)).c_str(), "in [0, 1)", opt.c1 + opt.c2 * s);
    require(opt.rebound_ratio >= 0 && opt.rebound_ratio <= 1, "--rebound", "in [0, 1]",
            opt.rebound_ratio);
    require(opt.quadrature_points >= 9, "--points", ">= 9", opt.quadrature_points);
    if (dist_slip) {
      require(*dist_slip >= 0 && *dist_slip <= 1, "--distribution", "a slip in [0, 1]", *dist_slip);
      require(opt.c1 + opt.c2 * *dist_slip < 1, "--distribution: c1 + c2 s", "< 1",
              opt.c1 + opt.c2 * *dist_slip);
      require(dist_points >= 2, "--distribution-points", ">= 2", dist_points);
    }
    soil = load_soil_file(soil_path);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wong-reece: %s\n", e.what());
    return wheelsim::cli::kExitUsage;
  }

  try {
    std::printf("# wong-reece %s: soil \"%s\" (%s); wheel R = %g m, b = %g m; load W = %g N\n",
                WHEELSIM_VERSION, soil.name.c_str(), soil_path.c_str(), radius, width, load);
    std::printf("# c1 = %g, c2 = %g, rebound ratio = %g, %d quadrature nodes per region\n", opt.c1,
                opt.c2, opt.rebound_ratio, opt.quadrature_points);
    std::printf("%8s %13s %12s %17s %14s %12s %14s\n", "slip [-]", "sinkage [mm]", "theta1 [deg]",
                "drawbar pull [N]", "torque [N m]", "F_T = T/R [N]", "efficiency [-]");
    std::vector<WongReeceResult> results;
    for (double s : slips) {
      const WongReeceResult r = solve_wong_reece(soil, wheel, load, s, opt);
      std::printf("%8.3f %13.3f %12.3f %17.1f %14.1f %12.1f %14.4f\n", s, r.sinkage_m * 1e3,
                  r.entry_angle_rad * kRadToDeg, r.drawbar_pull_N, r.torque_Nm, r.traction_force_N,
                  r.tractive_efficiency);
      results.push_back(r);
    }
    if (!csv_path.empty()) {
      std::ofstream csv(csv_path);
      if (!csv)
        throw UsageError("--csv: cannot write " + csv_path);
      csv << "slip,sinkage_m,entry_angle_rad,exit_angle_rad,max_stress_angle_rad,drawbar_pull_N,"
             "torque_Nm,traction_force_N,tractive_efficiency\n";
      csv.precision(10);
      for (const auto &r : results)
        csv << r.slip << ',' << r.sinkage_m << ',' << r.entry_angle_rad << ',' << r.exit_angle_rad
            << ',' << r.max_stress_angle_rad << ',' << r.drawbar_pull_N << ',' << r.torque_Nm << ','
            << r.traction_force_N << ',' << r.tractive_efficiency << '\n';
    }
    if (dist_slip) {
      WongReeceOptions d = opt;
      d.distribution_points = dist_points;
      const WongReeceResult r = solve_wong_reece(soil, wheel, load, *dist_slip, d);
      std::printf("\n# stress distribution at slip %g: theta1 = %.3f deg, theta_m = %.3f deg, "
                  "theta2 = %.3f deg\n",
                  *dist_slip, r.entry_angle_rad * kRadToDeg, r.max_stress_angle_rad * kRadToDeg,
                  r.exit_angle_rad * kRadToDeg);
      std::printf("%12s %12s %12s %10s\n", "theta [deg]", "sigma [kPa]", "tau [kPa]", "j [mm]");
      for (const auto &p : r.distribution)
        std::printf("%12.3f %12.3f %12.3f %10.3f\n", p.theta_rad * kRadToDeg, p.sigma_Pa / 1e3,
                    p.tau_Pa / 1e3, p.shear_displacement_m * 1e3);
      if (!dist_csv_path.empty()) {
        std::ofstream csv(dist_csv_path);
        if (!csv)
          throw UsageError("--distribution-csv: cannot write " + dist_csv_path);
        csv.precision(10);
        csv << "theta_rad,sigma_Pa,tau_Pa,shear_displacement_m\n";
        for (const auto &p : r.distribution)
          csv << p.theta_rad << ',' << p.sigma_Pa << ',' << p.tau_Pa << ','
              << p.shear_displacement_m << '\n';
      }
    }
  } catch (const UsageError &e) {
    std::fprintf(stderr, "wong-reece: %s\n", e.what());
    return wheelsim::cli::kExitUsage;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wong-reece: %s\n", e.what());
    return wheelsim::cli::kExitFailure;
  }
  return wheelsim::cli::kExitSuccess;
}
