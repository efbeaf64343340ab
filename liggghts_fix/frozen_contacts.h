// The contact histories of pairs that LIGGGHTS does not compute while both particles are frozen
// (fix wheel/active, docs/fix-wheel-active.md, "Contact history").
//
// LIGGGHTS 3.8 keeps pair contact history in the granular neighbour list. On every list rebuild,
// fix contacthistory (FixContactHistory) first copies the history of every touching pair of the
// old list into per-atom partner arrays (pre_exchange), the atoms migrate with those arrays, and
// the new list takes the history of each touching pair back from them (Neighbor::granular_*).
// A pair excluded from the list (`neigh_modify exclude group FROZEN FROZEN`) is not in the old
// list at the next rebuild, so its history would be lost. FrozenContacts keeps it: between the
// exchange and the build (pre_neighbor) it
//   - takes out of the partner arrays of each frozen particle the entries whose partner is frozen
//     too (those pairs will be excluded) and keeps them with the particle;
//   - puts back into the partner arrays every kept entry whose pair is computed again (one of the
//     two particles active), so that the build restores it as if the pair had never been left out.
// Frozen particles do not move, so a kept history is still the pair's history when it comes back.
//
// Per particle the kept entries are [tag, h_1 .. h_dnum] each, from the particle's own side (the
// same values fix contacthistory holds for it), and they follow the particle across ranks and
// into restart files (the fix's per-atom callbacks call the pack/unpack functions here).
#ifndef WHEELSIM_FROZEN_CONTACTS_H
#define WHEELSIM_FROZEN_CONTACTS_H

#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
class FixContactHistory;
} // namespace LAMMPS_NS

namespace wheelsim {

class FrozenContacts {
public:
  explicit FrozenContacts(LAMMPS_NS::LAMMPS *lmp) : lmp_(lmp) {}

  /// Binds to the run's fix contacthistory (nullptr: the pair style keeps no history, or the
  /// histories are not to be kept; then every kept entry is dropped). Returns false if kept
  /// entries have another width than 1 + its dnum (the contact model changed since they were
  /// written).
  bool bind(LAMMPS_NS::FixContactHistory *history);
  int entry_width() const { return width_; }

  /// Between exchange and neighbour build: see the file comment. frozen_bit: the mask bit of the
  /// frozen particles (owned and ghost masks must be current).
  void sync(int frozen_bit);

  long kept_local() const; ///< kept entries on this rank

  // per-atom storage, called from the fix's callbacks
  void grow(int nmax) { kept_.resize(nmax); }
  void copy(int i, int j) { kept_[j] = kept_[i]; }
  void clear(int i) { kept_[i].clear(); }
  int pack(int i, double *buf) const; ///< [n, width, entries]
  int unpack(int i, const double *buf);
  int packed_size(int i) const;
  int max_packed_size_local() const;

private:
  void put_back(int i, const double *entries, int count); // into the partner arrays of atom i

  LAMMPS_NS::LAMMPS *lmp_;
  LAMMPS_NS::FixContactHistory *history_ = nullptr;
  int dnum_ = 0;
  int width_ = 0; ///< 1 + dnum once bound or read; 0 = unknown
  std::vector<std::vector<double>> kept_;
  std::vector<double> scratch_;
};

} // namespace wheelsim

#endif
