/* fix wheelsim/tile_history — carry the pair contact histories of a settled periodic block into
   the bed tiled from it (inputs/soilbin/tile.in, docs/soil-bins.md "Tiled beds").

   fix ID all wheelsim/tile_history block L
   ... replicate N 1 1 offset L 0 0 shift 0 0 0, change_box, delete_atoms ...
   fix_modify ID remap keep          (or drop)
   run 0                             (optional: the force check below)
   unfix ID

   LIGGGHTS 3.8's `replicate` copies each grain with its partner arrays, but the copies get new
   IDs (and `delete_atoms` renumbers every grain), while a pair's history is found by the
   partner's ID: without this fix every grain-grain contact of a tiled bed starts again from zero
   tangential displacement, and the bed has to re-mobilise its friction while it relaxes.

   At creation (the block settled, x periodic with period L) the fix records for every grain of
   the group its ID, its x and its contact histories [partner ID, values] (the current ones: the
   pair's list is copied into the partner arrays first). These records follow the grains through
   `replicate` (copied with them), `delete_atoms` and `change_box` (migration). `fix_modify ID
   remap keep` then rewrites every grain's partner arrays: a grain that is copy k of block grain
   b (k = round((x - x_b)/L)) had partner p in the block; its partner now is the copy k' of p,
   k' in {k-1, k, k+1} the one nearest in x (a contact across the block's periodic seam joins
   neighbouring copies), found by block ID and copy number among all grains. Entries whose
   partner copy no longer exists (cut at the bin's end planes) are dropped. The next run starts
   from these histories. The per-atom values of every fix property/atom recorded at creation
   (among them the primitive walls' contact histories) are restored too: LIGGGHTS 3.8's
   `replicate` resets them, and fix contacthistory's partner counts, to their defaults in every
   grain, copies and originals alike. `remap drop` clears the pair histories instead and leaves
   the rest as replicate left it (every contact starts from zero, as without the fix).

   Check: at the set-up of the next run the fix compares, over the grains that kept every
   contact of the block (none of their partners cut; no grain touches the new end walls, those
   were cut), each grain's force with its force at the block's last step, and prints the rms
   and the largest difference. Even the untouched block does not give zero (the set-up's damping
   sees the velocities at the end of the step, the step itself those of its middle): on the ci
   soil remap keep gives the block's own residual (docs/soil-bins.md "Tiled beds").
   The fix does nothing else; unfix it afterwards.

   Global vector (5), after the remap: 1 grains remapped, 2 history entries kept, 3 entries kept
   across the block's seam (k' != k), 4 entries dropped (partner copy deleted), 5 the force
   check's rms |f - f_block| [N] (after the next set-up).

   The FixStyle block is in the form LIGGGHTS' Make.sh expects (docs/building.md). */

#ifdef FIX_CLASS

// clang-format off
FixStyle(wheelsim/tile_history,FixTileHistory)
// clang-format on

#else

#ifndef LMP_FIX_TILE_HISTORY_H
#define LMP_FIX_TILE_HISTORY_H

#include "fix.h"

#include <array>
#include <string>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {

class FixContactHistory;

class FixTileHistory : public Fix {
public:
  FixTileHistory(class LAMMPS *lmp, int narg, char **arg);
  ~FixTileHistory() override;

  int setmask() override { return 0; }
  void setup(int vflag) override; // the force check after a remap
  int modify_param(int narg, char **arg) override;
  double compute_vector(int i) override;

  // the per-grain records follow the grains (replicate copies, delete_atoms, migration)
  double memory_usage() override;
  void grow_arrays(int nmax) override;
  void copy_arrays(int i, int j, int delflag) override;
  void set_arrays(int i) override;
  int pack_exchange(int i, double *buf) override;
  int unpack_exchange(int nlocal, double *buf) override;

private:
  void record();
  void remap(bool keep);
  void carry(int i, bool save); // grain i's fix property/atom values: into the record or back
  [[noreturn]] void bad_argument(const char *fmt, ...);

  FixContactHistory *history_;
  double block_length_; // L [m]
  int width_;           // 1 + dnum
  bool remapped_;
  bool check_pending_; // compare the next set-up's forces with the block's
  // per grain: block ID (0: not recorded, e.g. outside the group), its x in the block, its
  // entries [partner block ID, values] from its own side
  std::vector<int> block_tag_;
  std::vector<double> block_x_;
  std::vector<std::array<double, 3>> block_f_; // the grain's force at the block's last step [N]
  std::vector<char> complete_;                 // every contact of the block kept (after remap)
  std::vector<std::vector<double>> entries_;
  // the fixes property/atom whose per-atom values are carried (replicate resets them), and
  // per grain their values, carried_width_ per grain
  struct Carried {
    std::string id;
    int cols;
  };
  std::vector<Carried> carried_;
  int carried_width_;
  std::vector<double> carried_values_;
  // every block grain's x, by block ID (the partner's position decides its copy)
  std::unordered_map<int, double> block_x_of_tag_;
  double vector_[5];
};

} // namespace LAMMPS_NS

#endif
#endif
