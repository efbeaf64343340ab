// Registration of wheelsim's LIGGGHTS styles into an existing LIGGGHTS instance.
//
// Debian's LIGGGHTS 3.8 has no plugin loader: the fix styles a deck may use are those compiled
// into Modify::fix_map. liggghts-wheel links the unmodified libliggghts, creates the LAMMPS
// instance and then calls register_wheelsim_styles() before reading the input, so every style
// declared with a `FixStyle(name,Class)` block in a header of this folder becomes available.
// The same headers build unchanged inside a LIGGGHTS source tree (docs/building.md).
#ifndef WHEELSIM_STYLE_REGISTRATION_H
#define WHEELSIM_STYLE_REGISTRATION_H

#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace wheelsim {

/// Style names (e.g. "wheel/cosim") this build adds to LIGGGHTS, in declaration order.
std::vector<std::string> wheelsim_fix_style_names();

/// Inserts every wheelsim fix style into lmp->modify's style map. Call once, after the LAMMPS
/// constructor and before the input is read. A name that LIGGGHTS already defines is an error
/// (std::runtime_error naming the style): we never silently replace a built-in style.
void register_wheelsim_styles(LAMMPS_NS::LAMMPS *lmp);

} // namespace wheelsim

#endif
