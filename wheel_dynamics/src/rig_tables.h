// Private to wheelsim_rig: the keys and the parser of each rig-config table that has no variants
// ([wheel], [rig], [motor], [run], [output]); [carriage] is in slip_modes.cpp, [terrain] in
// terrain_registry.cpp and terrains/. One function per table.
#pragma once

#include <string>
#include <vector>

#include "config_table.h"
#include "wheelsim/rig/config_schema.h"

namespace wheelsim::rig::detail {

std::vector<ConfigKey> wheel_keys();
std::vector<ConfigKey> rig_keys();
std::vector<ConfigKey> motor_keys();
std::vector<ConfigKey> run_keys();
std::vector<ConfigKey> output_keys();

void parse_wheel(const Table &t, const std::string &base_dir, RigConfig &c);
void parse_rig(const Table &t, RigConfig &c);
/// `carriage_mode`: carriage.mode as written ("" if absent; checked in full by [carriage]).
void parse_motor(const Table &t, const std::string &carriage_mode, RigConfig &c);
void parse_run(const Table &t, RigConfig &c);
void parse_output(const Table &t, RigConfig &c);

} // namespace wheelsim::rig::detail
