// wheel-mesh: writes the closed triangle mesh of a rigid lugged (or smooth) wheel in metres and
// prints its mass properties. Reference: docs/wheel-mesh.md.
//
// Exit status (wheelsim/cli.h): 0 done (also --help, --version), 1 a mesh could not be written,
// 2 bad command line, parameters (WheelSpecError: out of range, implausible size, lugs that
// overlap) or catalogue.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>

#include "catalog.h"
#include "wheel_output.h"
#include "wheelsim/cli.h"
#include "wheelsim/geometry/mesh_error.h"

namespace wm = wheelsim::meshes;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void run_one(const std::string &name, const wm::WheelSpec &spec, double density,
             const std::string &prefix, const std::vector<std::string> &formats,
             const std::string &props_path) {
  const auto t0 = std::chrono::steady_clock::now();
  const wm::GeneratedWheel wheel = wm::generate_wheel(spec, density);
  std::vector<std::string> files;
  if (!prefix.empty())
    files = wm::write_wheel(wheel.mesh, prefix, formats);
  if (!props_path.empty())
    wm::write_properties(props_path, name, spec, wheel, files);
  std::cout << wm::format_properties(name, spec, wheel);
  for (const auto &f : files)
    std::cout << "  wrote " << f << "\n";
  if (!props_path.empty())
    std::cout << "  wrote " << props_path << "\n";
  // Timing goes to stdout only, never into result files.
  std::cout << "  generated in " << seconds_since(t0) << " s\n";
}

} // namespace

int main(int argc, char **argv) {
  CLI::App app{
      "wheel-mesh: closed, outward-oriented triangle mesh of a rigid lugged wheel in metres "
      "(wheel frame: centre at the origin, axle +y, x forward, z up). See "
      "docs/wheel-mesh.md."};
  wm::WheelSpec spec;
  std::optional<std::string> type_name;
  double density = 7850.0;
  std::string out_prefix, props_path, catalog_path, out_dir;
  std::vector<std::string> formats{"obj", "stl"};

  app.add_option("--diameter", spec.diameter_m, "outer diameter over the lugs D0 [m]");
  app.add_option("--width", spec.width_m, "wheel width w [m] (y in [-w/2, w/2])");
  app.add_option("--lugs", spec.lug_count, "lug count nl (0 without --type: smooth cylinder)");
  app.add_option("--lug-height", spec.lug_height_m, "lug height lh [m]; rim radius D0/2 - lh");
  app.add_option("--lug-width", spec.lug_width_m, "lug width (thickness) on the lug top [m]")
      ->capture_default_str();
  app.add_option("--lug-angle", spec.lug_angle_deg, "lug angle delta to the axle [deg], 0..70")
      ->capture_default_str();
  app.add_option("--centre-length", spec.centre_length_m,
                 "lug centre length h [m] (combined, nondirectional)")
      ->capture_default_str();
  app.add_option("--type", type_name, "lug type: straight, combined or nondirectional");
  app.add_flag("--smooth", spec.smooth, "smooth cylinder of diameter D0 (no lugs)");
  app.add_option("--max-arc", spec.resolution.max_arc_m,
                 "max circumferential segment length on the outer radius [m]")
      ->capture_default_str();
  app.add_option("--max-angle", spec.resolution.max_angle_deg,
                 "max circumferential segment angle [deg]")
      ->capture_default_str();
  app.add_option("--max-width-edge", spec.resolution.max_width_edge_m,
                 "max edge along the width and radially on the side discs [m]")
      ->capture_default_str();
  app.add_option("--density", density, "density for the mass properties [kg/m^3]")
      ->capture_default_str();
  app.add_option("--out", out_prefix, "write <OUT>.obj, <OUT>.stl (see --formats)");
  app.add_option("--formats", formats, "mesh formats to write: obj, stl (ascii), ply")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--props", props_path,
                 "write the mass properties to this file (.toml or .json by extension)");
  auto *catalog_opt = app.add_option(
      "--catalog", catalog_path, "generate every [[wheel]] of this TOML catalogue into --out-dir");
  app.add_option("--out-dir", out_dir, "output directory for --catalog")->needs(catalog_opt);

  wheelsim::cli::setup(app, "wheel-mesh");
  if (const auto status = wheelsim::cli::parse(app, argc, argv))
    return *status;
  using wheelsim::cli::UsageError;

  try {
    if (!catalog_path.empty()) {
      for (const char *opt : {"--diameter", "--width", "--lugs", "--type", "--out", "--props"}) {
        if (app.count(opt) > 0) {
          throw UsageError(std::string(opt) +
                           " cannot be combined with --catalog (set it in the catalogue)");
        }
      }
      if (out_dir.empty())
        throw UsageError("--catalog needs --out-dir");
      const auto entries = wm::read_catalog(catalog_path);
      std::filesystem::create_directories(out_dir);
      const auto t0 = std::chrono::steady_clock::now();
      for (const auto &e : entries) {
        const std::string prefix = (std::filesystem::path(out_dir) / e.name).string();
        run_one(e.name, e.spec, e.density_kg_m3, prefix, formats, prefix + ".props.toml");
      }
      std::cout << entries.size() << " wheels generated in " << seconds_since(t0) << " s\n";
      return 0;
    }
    if (app.count("--diameter") == 0)
      throw UsageError("--diameter is required [m]");
    if (app.count("--width") == 0)
      throw UsageError("--width is required [m]");
    if (!spec.smooth) {
      if (app.count("--lugs") == 0) {
        throw UsageError("--lugs is required (or --smooth for a smooth cylinder)");
      }
      if (spec.lug_count == 0 && !type_name) {
        spec.smooth = true; // --lugs 0 without a lug type: smooth cylinder
      } else {
        if (!type_name)
          throw UsageError("--type is required for a lugged wheel");
        spec.type = wm::parse_lug_type(*type_name);
        if (app.count("--lug-height") == 0 && spec.lug_count > 0) {
          throw UsageError("--lug-height is required for a lugged wheel [m]");
        }
        if (spec.type != wm::LugType::straight && app.count("--centre-length") == 0) {
          throw UsageError(std::string("--centre-length is required for ") +
                           wm::to_string(spec.type) + " lugs [m]");
        }
      }
    } else if (type_name) {
      throw UsageError("--type cannot be combined with --smooth");
    }
    const std::string name =
        out_prefix.empty() ? "wheel" : std::filesystem::path(out_prefix).filename().string();
    run_one(name, spec, density, out_prefix, formats, props_path);
    return wheelsim::cli::kExitSuccess;
  } catch (const UsageError &e) {
    return wheelsim::cli::report_usage_error("wheel-mesh", e.what());
  } catch (const wm::WheelSpecError &e) {
    std::cerr << "wheel-mesh: error: " << e.what() << "\n";
    return wheelsim::cli::kExitUsage;
  } catch (const std::exception &e) {
    std::cerr << "wheel-mesh: error: " << e.what() << "\n";
    return wheelsim::cli::kExitFailure;
  }
}
