// Reading and rewriting the per-atom partner arrays of LIGGGHTS 3.8's fix contacthistory: the
// one place that reaches into them (used by frozen_contacts.cpp and fix_tile_history.cpp).
//
// How LIGGGHTS keeps a pair's contact history: between neighbour-list builds it lives in the
// granular neighbour list; at each rebuild fix contacthistory first copies the history of every
// touching pair into per-atom partner arrays (pre_exchange: for atom i, npartner[i] entries of
// [partner tag, dnum values], the values as seen from i), the atoms migrate with those arrays,
// and the new list takes each touching pair's history back from them, matched by the partner's
// tag. A run's set-up does the same copy only if the pair style was computed since the last one
// (PairGran's "computeflag"), so arrays rewritten between runs survive into the next run.
#pragma once

#include "comm.h"
#include "error.h"
#include "fix_contact_history.h"
#include "lammps.h"
#include "my_page.h"

#include <algorithm>

namespace wheelsim {

// fix contacthistory's partner arrays are protected members (LIGGGHTS lets only Neighbor and
// PairGran, its friends, touch them). A class derived from it may name them, and a pointer to
// a member formed through the derived class has the type `T FixContactHistory::*`, which can be
// applied to any FixContactHistory: standard C++, no layout assumption. No object of this type
// is ever created.
struct ContactHistoryAccess : LAMMPS_NS::FixContactHistory {
  static int *FixContactHistory::*npartner() { return &ContactHistoryAccess::npartner_; }
  static int **FixContactHistory::*partner() { return &ContactHistoryAccess::partner_; }
  static double **FixContactHistory::*values() { return &ContactHistoryAccess::contacthistory_; }
  static int FixContactHistory::*maxtouch() { return &ContactHistoryAccess::maxtouch_; }
  static LAMMPS_NS::MyPage<int> *FixContactHistory::*ipage() {
    return &ContactHistoryAccess::ipage_;
  }
  static LAMMPS_NS::MyPage<double> *FixContactHistory::*dpage() {
    return &ContactHistoryAccess::dpage_;
  }
};

/// Replaces atom i's partner arrays by `count` entries of [tag, h_1 .. h_dnum] (width 1 + dnum).
/// New chunks come from fix contacthistory's own pages, as its unpack_exchange takes them; the
/// old chunk is orphaned until the pages are reset at the next pre_exchange (as LIGGGHTS does
/// for migrating atoms). `who` names the caller in the overflow error.
inline void replace_partners(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::FixContactHistory &h, int i,
                             const double *entries, int count, const char *who) {
  using A = ContactHistoryAccess;
  const int dnum = h.get_dnum();
  const int width = 1 + dnum;
  int *new_partner = (h.*A::ipage())->get(count);
  double *new_values = (h.*A::dpage())->get(count * dnum);
  if (new_partner == nullptr || new_values == nullptr) {
    char msg[256];
    snprintf(msg, sizeof(msg),
             "%s: contact history overflow (%d partners of one particle); "
             "boost neigh_modify one",
             who, count);
    lmp->error->one(FLERR, msg);
  }
  for (int e = 0; e < count; ++e) {
    new_partner[e] = static_cast<int>(entries[e * width]);
    std::copy(entries + e * width + 1, entries + (e + 1) * width, new_values + e * dnum);
  }
  (h.*A::partner())[i] = new_partner;
  (h.*A::values())[i] = new_values;
  (h.*A::npartner())[i] = count;
  int &maxtouch = h.*A::maxtouch();
  maxtouch = std::max(maxtouch, count);
  lmp->comm->maxexchange_fix = std::max(lmp->comm->maxexchange_fix, width * maxtouch + 1);
}

} // namespace wheelsim
