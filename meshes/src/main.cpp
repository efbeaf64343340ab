// wheel-mesh: writes the closed triangle mesh of a rigid lugged (or smooth) wheel in metres and
// prints its mass properties. Reference: docs/wheel-mesh.md.
// wheel-mesh tool KIND ...: the same for the rigid tools of the virtual soil lab (plates, shear
// box frames, rings). Reference: docs/tool-mesh.md.
//
// Exit status (wheelsim/cli.h): 0 done (also --help, --version), 1 a mesh could not be written,
// 2 bad command line, parameters (WheelSpecError, ToolSpecError: out of range, implausible size,
// lugs that overlap, a hole as large as the body) or catalogue.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "catalog.h"
#include "tool_spec.h"
#include "wheel_output.h"
#include "wheelsim/cli.h"
#include "wheelsim/geometry/mesh_error.h"

namespace wm = wheelsim::meshes;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Writes a generated solid (wheel or tool): mesh files under `prefix` (none if empty), the mass
/// properties to `props_path` (none if empty), and prints the properties and what was written.
/// Timing goes to stdout only, never into result files.
template <class Spec>
void write_solid(const std::string &name, const Spec &spec, const wm::GeneratedSolid &solid,
                 const std::string &prefix, const std::vector<std::string> &formats,
                 const std::string &props_path, std::chrono::steady_clock::time_point t0) {
  std::vector<std::string> files;
  if (!prefix.empty())
    files = wm::write_mesh_files(solid.mesh, prefix, formats);
  if (!props_path.empty())
    wm::write_properties(props_path, name, spec, solid, files);
  std::cout << wm::format_properties(name, spec, solid);
  for (const auto &f : files)
    std::cout << "  wrote " << f << "\n";
  if (!props_path.empty())
    std::cout << "  wrote " << props_path << "\n";
  std::cout << "  generated in " << seconds_since(t0) << " s\n";
}

void run_one(const std::string &name, const wm::WheelSpec &spec, double density,
             const std::string &prefix, const std::vector<std::string> &formats,
             const std::string &props_path) {
  const auto t0 = std::chrono::steady_clock::now();
  write_solid(name, spec, wm::generate_wheel(spec, density), prefix, formats, props_path, t0);
}

/// The tool mode in brief: the footer of `wheel-mesh --help`, and `wheel-mesh tool --help`.
std::string tools_overview() {
  std::ostringstream os;
  os << "Tools (rigid tools of the virtual soil lab; centred at the origin, z up, metres; "
        "docs/tool-mesh.md):\n";
  for (const auto &t : wm::tool_syntaxes()) {
    const std::string call = std::string("wheel-mesh tool ") + t.name + " " + t.parameters;
    os << "  " << call << std::string(call.size() < 44 ? 44 - call.size() : 1, ' ') << t.summary
       << "\n";
  }
  os << "  options: --out PREFIX, --formats obj,stl,ply, --props FILE, --density RHO, "
        "--max-edge E; round tools: --chord-error F\n"
        "  'wheel-mesh tool KIND --help' lists a tool's parameters and options.\n";
  return os.str();
}

/// `wheel-mesh tool KIND ...`; argv[0] is "tool".
int tool_main(int argc, char **argv) {
  const std::string program = "wheel-mesh tool";
  std::vector<std::string> names;
  for (const auto &t : wm::tool_syntaxes())
    names.push_back(t.name);
  if (argc < 2) {
    return wheelsim::cli::report_usage_error(
        program, "expected a tool: plate-rect, plate-disc, frame or ring");
  }
  const std::string kind_name = argv[1];
  if (kind_name == "--help" || kind_name == "-h") {
    std::cout << "Usage: wheel-mesh tool KIND PARAMETERS... [OPTIONS]\n\n" << tools_overview();
    return wheelsim::cli::kExitSuccess;
  }
  if (kind_name == "--version") {
    std::cout << wheelsim::cli::version_line("wheel-mesh") << "\n";
    return wheelsim::cli::kExitSuccess;
  }
  const auto syntax = std::find_if(wm::tool_syntaxes().begin(), wm::tool_syntaxes().end(),
                                   [&](const wm::ToolSyntax &t) { return kind_name == t.name; });
  if (syntax == wm::tool_syntaxes().end()) {
    std::string message = "unknown tool '" + kind_name + "'";
    const std::string near = wheelsim::cli::nearest_option(kind_name, names);
    if (!near.empty())
      message += " (did you mean '" + near + "'?)";
    return wheelsim::cli::report_usage_error(
        program, message + "; expected plate-rect, plate-disc, frame or ring");
  }

  wm::ToolSpec spec;
  spec.kind = syntax->kind;
  double density = 7850.0;
  std::string out_prefix, props_path;
  std::vector<std::string> formats{"obj", "stl"};
  CLI::App app{std::string(syntax->summary) +
               ". Body frame: centred at the origin, z up; sizes in metres. See "
               "docs/tool-mesh.md."};
  const char *segments_help = "segments around the circle, 8..100000 (default: from --chord-error)";
  switch (spec.kind) {
  case wm::ToolKind::plate_rect:
    app.add_option("LX", spec.lx_m, "plate length along x [m]")->required();
    app.add_option("LY", spec.ly_m, "plate width along y [m]")->required();
    app.add_option("T", spec.height_m, "plate thickness along z [m]")->required();
    break;
  case wm::ToolKind::plate_disc:
    app.add_option("R", spec.radius_m, "plate radius [m]")->required();
    app.add_option("T", spec.height_m, "plate thickness along z [m]")->required();
    app.add_option("SEGMENTS", spec.segments, segments_help);
    break;
  case wm::ToolKind::frame:
    app.add_option("LX", spec.lx_m, "hole (inner) length along x [m]")->required();
    app.add_option("LY", spec.ly_m, "hole (inner) width along y [m]")->required();
    app.add_option("WALL", spec.wall_m,
                   "wall thickness [m]; the outer size is (LX + 2 WALL) x (LY + 2 WALL)")
        ->required();
    app.add_option("H", spec.height_m, "frame height along z [m]")->required();
    break;
  case wm::ToolKind::ring:
    app.add_option("RI", spec.inner_radius_m, "inner radius [m], < RO")->required();
    app.add_option("RO", spec.radius_m, "outer radius [m]")->required();
    app.add_option("H", spec.height_m, "ring height along z [m]")->required();
    app.add_option("SEGMENTS", spec.segments, segments_help);
    break;
  }
  if (spec.round()) {
    app.add_option("--chord-error", spec.chord_error,
                   "largest chord error (sagitta) as a fraction of the (outer) radius, when "
                   "SEGMENTS is not given")
        ->capture_default_str();
  }
  app.add_option("--max-edge", spec.max_edge_m,
                 "largest edge on the faces and walls [m] (and along the circle unless SEGMENTS "
                 "is given); 0: no subdivision")
      ->capture_default_str();
  app.add_option("--density", density, "density for the mass properties [kg/m^3]")
      ->capture_default_str();
  app.add_option("--out", out_prefix, "write <OUT>.obj, <OUT>.stl (see --formats)");
  app.add_option("--formats", formats, "mesh formats to write: obj, stl (ascii), ply")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--props", props_path,
                 "write the mass properties to this file (.toml or .json by extension)");
  const std::string tool_program = program + " " + syntax->name;
  wheelsim::cli::setup(app, tool_program);
  app.set_version_flag("--version", wheelsim::cli::version_line("wheel-mesh"));
  if (const auto status = wheelsim::cli::parse(app, argc - 1, argv + 1))
    return *status;

  try {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string name =
        out_prefix.empty() ? syntax->name : std::filesystem::path(out_prefix).filename().string();
    write_solid(name, spec, wm::generate_tool(spec, density), out_prefix, formats, props_path, t0);
    return wheelsim::cli::kExitSuccess;
  } catch (const wm::ToolSpecError &e) {
    std::cerr << tool_program << ": error: " << e.what() << "\n";
    return wheelsim::cli::kExitUsage;
  } catch (const wm::WheelSpecError &e) { // --formats
    std::cerr << tool_program << ": error: " << e.what() << "\n";
    return wheelsim::cli::kExitUsage;
  } catch (const std::exception &e) {
    std::cerr << tool_program << ": error: " << e.what() << "\n";
    return wheelsim::cli::kExitFailure;
  }
}

} // namespace

int main(int argc, char **argv) {
  if (argc >= 2 && std::string(argv[1]) == "tool")
    return tool_main(argc - 1, argv + 1);
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
  app.footer(tools_overview() + "\n" + app.get_footer());
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
