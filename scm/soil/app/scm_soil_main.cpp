// scm-soil: converts SCM soil parameters between our soil files (inputs/scm_soils/*.toml) and
// Project Chrono's SCM JSON (either of its two layouts), keeping Chrono's names and units.
//   scm-soil import CHRONO.json [--out SOIL.toml] [--name NAME]
//   scm-soil export SOIL.toml [--out CHRONO.json] [--format terrain-node|soil-parameters]
//                   [--patch-length M] [--patch-width M] [--grid-spacing M]
// Docs: docs/chrono-interop.md.
#include "wheelsim/cli.h"
#include "wheelsim/scm/chrono_soil.h"
#include "wheelsim/scm/soil_file.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace {

using namespace wheelsim::scm;
namespace cli = wheelsim::cli;

constexpr const char *kProgram = "scm-soil";

/// Writes `text` to `path`, or to stdout when `path` is empty or "-". Returns false on failure
/// (message printed).
bool write_output(const std::string &path, const std::string &text) {
  if (path.empty() || path == "-") {
    std::cout << text;
    std::cout.flush();
    return static_cast<bool>(std::cout);
  }
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    std::fprintf(stderr, "%s: cannot write '%s'\n", kProgram, path.c_str());
    return false;
  }
  return true;
}

int run_import(const std::string &input, const std::string &output, const std::string &name) {
  ChronoLayout layout;
  const ChronoSoil chrono = load_chrono_soil(input, &layout);
  SoilParameters soil = to_soil_parameters(chrono);
  if (!name.empty())
    soil.name = name;
  if (soil.name.empty())
    soil.name = std::filesystem::path(input).stem().string();
  const std::string file = std::filesystem::path(input).filename().string();
  const std::string object =
      layout == ChronoLayout::terrain_node ? "Soil parameters" : "Soil Parameters";
  SoilFileNotes notes;
  notes.description = "imported by scm-soil from the Chrono JSON " + file + " (" +
                      chrono_layout_name(layout) + " layout)";
  for (const ChronoSoilKey &k : chrono_soil_keys())
    notes.sources.emplace_back(
        k.soil_file_key,
        "Chrono JSON " + file + ", \"" + object + "\".\"" +
            (layout == ChronoLayout::terrain_node ? k.terrain_node_name : k.soil_parameters_name) +
            "\"" + (std::string(k.unit) == "deg" ? " [deg]" : ""));
  const std::string text = write_soil_file(soil, notes);
  // The file written must load as it will be used (a check of the writer, not of the input).
  (void)parse_soil_file(text, output.empty() ? "<scm-soil output>" : output);
  if (!write_output(output, text))
    return cli::kExitFailure;
  if (!output.empty() && output != "-")
    std::fprintf(stderr, "%s: wrote %s (soil \"%s\", from the %s layout)\n", kProgram,
                 output.c_str(), soil.name.c_str(), chrono_layout_name(layout));
  return cli::kExitSuccess;
}

int run_export(const std::string &input, const std::string &output, const std::string &format,
               const ChronoTerrainNodeSettings &settings) {
  const ChronoLayout layout = chrono_layout_from_name(format);
  const SoilParameters soil = load_soil_file(input);
  const std::string text = write_chrono_soil(to_chrono_soil(soil), layout, settings);
  if (!write_output(output, text))
    return cli::kExitFailure;
  if (!output.empty() && output != "-")
    std::fprintf(stderr, "%s: wrote %s (soil \"%s\", %s layout)\n", kProgram, output.c_str(),
                 soil.name.c_str(), chrono_layout_name(layout));
  return cli::kExitSuccess;
}

void require_length(double v, const char *option) {
  if (!(v > 0 && std::isfinite(v)))
    throw cli::UsageError(std::string(option) + " must be > 0 m, got " + std::to_string(v));
}

} // namespace

int main(int argc, char **argv) {
  CLI::App app{"scm-soil: SCM soil files (TOML) to and from Project Chrono's SCM soil JSON, with "
               "Chrono's names and units (docs/chrono-interop.md)"};
  app.require_subcommand(1);
  std::string input, output, name, format = "terrain-node";
  ChronoTerrainNodeSettings settings;

  CLI::App *import_cmd =
      app.add_subcommand("import", "Chrono SCM JSON (either layout) -> soil file (TOML)");
  import_cmd->add_option("chrono_json", input, "Chrono JSON file to read")->required();
  import_cmd->add_option("--out,-o", output, "soil file to write (default: standard output)");
  import_cmd->add_option("--name", name,
                         "soil name (default: the JSON's \"Name\", else the file name)");

  CLI::App *export_cmd = app.add_subcommand("export", "soil file (TOML) -> Chrono SCM JSON");
  export_cmd->add_option("soil_file", input, "soil file to read (inputs/scm_soils/*.toml)")
      ->required();
  export_cmd->add_option("--out,-o", output, "JSON file to write (default: standard output)");
  export_cmd
      ->add_option("--format", format,
                   "terrain-node (co-simulation terrain spec, \"Soil parameters\"; default) or "
                   "soil-parameters (Chrono::Vehicle SCM soil-parameter file)")
      ->check(CLI::IsMember({"terrain-node", "soil-parameters"}));
  export_cmd->add_option("--patch-length", settings.patch_length_m,
                         "terrain-node: \"Patch dimensions\" \"Length\" [m] (default 4)");
  export_cmd->add_option("--patch-width", settings.patch_width_m,
                         "terrain-node: \"Patch dimensions\" \"Width\" [m] (default 1)");
  export_cmd->add_option("--grid-spacing", settings.grid_spacing_m,
                         "terrain-node: \"Grid spacing\" [m] (default 0.05)");

  cli::setup(app, kProgram);
  if (const auto status = cli::parse(app, argc, argv))
    return *status;

  try {
    if (import_cmd->parsed())
      return run_import(input, output, name);
    require_length(settings.patch_length_m, "--patch-length");
    require_length(settings.patch_width_m, "--patch-width");
    require_length(settings.grid_spacing_m, "--grid-spacing");
    return run_export(input, output, format, settings);
  } catch (const cli::UsageError &e) {
    return cli::report_usage_error(kProgram, e.what());
  } catch (const ChronoSoilError &e) {
    std::fprintf(stderr, "%s: %s\n", kProgram, e.what());
    return cli::kExitUsage;
  } catch (const SoilFileError &e) {
    std::fprintf(stderr, "%s: %s\n", kProgram, e.what());
    return cli::kExitUsage;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "%s: error: %s\n", kProgram, e.what());
    return cli::kExitFailure;
  }
}
