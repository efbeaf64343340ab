// terrain.type = "dem": LIGGGHTS with fix wheel/cosim 'motion coupled', a remote terrain reached
// over the coupler (docs/coupling-protocol.md). No in-process factory: wheel-rig's coupling loop
// runs it and records /parameters/coupling/* from LIGGGHTS' Hello.
#include "terrains.h"

#include "../config_table.h"

namespace wheelsim::rig::terrains {
namespace dem_entry {

using detail::fmt;
using detail::Table;

ConfigKey dem(ConfigKey k) { return terrain_key("dem", std::move(k)); }

std::vector<ConfigKey> keys() {
  return {
      dem({"", "endpoint", "string", "", "", "ipc://... or tcp://..."}),
      dem({"", "timeout", "number", "s", fmt(TerrainConfig{}.timeout_s), "> 0"}),
  };
}

void parse(const Table &t, const std::string & /*base_dir*/, RigConfig &c) {
  const auto ep = t.string("endpoint");
  if (!ep)
    t.parser().fail(nullptr, "missing key 'terrain.endpoint': write e.g. terrain.endpoint = "
                             "\"ipc:///tmp/wheelsim.ipc\" or \"tcp://127.0.0.1:5555\"");
  if (ep->rfind("ipc://", 0) != 0 && ep->rfind("tcp://", 0) != 0)
    t.fail("endpoint", "terrain.endpoint must start with ipc:// or tcp://, got \"" + *ep + "\"");
  c.terrain.endpoint = *ep;
  c.terrain.timeout_s = t.positive("timeout", "s").value_or(c.terrain.timeout_s);
}

} // namespace dem_entry

TerrainKind dem_terrain() {
  using namespace dem_entry;
  return {"dem",
          TerrainType::dem,
          "LIGGGHTS particles over the coupler (remote)",
          keys(),
          parse,
          nullptr,
          nullptr,
          nullptr};
}

} // namespace wheelsim::rig::terrains
