// See frozen_contacts.h.
#include "frozen_contacts.h"

#include "atom.h"
#include "comm.h"
#include "contact_history_access.h"
#include "error.h"
#include "fix_contact_history.h"
#include "lammps.h"

#include <algorithm>
#include <cstring>

using LAMMPS_NS::FixContactHistory;

using HistoryAccess = wheelsim::ContactHistoryAccess;

namespace wheelsim {

bool FrozenContacts::bind(FixContactHistory *history) {
  history_ = history;
  dnum_ = history ? history->get_dnum() : 0;
  if (history_ == nullptr || dnum_ == 0) { // nothing to keep (history drop, or none at all)
    for (std::vector<double> &k : kept_)
      k.clear();
    width_ = 0;
    return true;
  }
  const int width = 1 + dnum_;
  bool consistent = true;
  for (const std::vector<double> &k : kept_)
    if (!k.empty() && width_ != 0 && width_ != width)
      consistent = false;
  if (!consistent)
    return false;
  width_ = width;
  return true;
}

void FrozenContacts::put_back(int i, const double *entries, int count) {
  FixContactHistory &h = *history_;
  int *npartner = h.*HistoryAccess::npartner();
  int **partner = h.*HistoryAccess::partner();
  double **values = h.*HistoryAccess::values();
  const int n_old = npartner[i];
  // only partners the arrays do not hold already
  int added = 0;
  scratch_.clear();
  for (int e = 0; e < count; ++e) {
    const double *entry = entries + e * width_;
    const int tag = static_cast<int>(entry[0]);
    bool present = false;
    for (int m = 0; m < n_old && !present; ++m)
      present = partner[i][m] == tag;
    if (!present) {
      scratch_.insert(scratch_.end(), entry, entry + width_);
      ++added;
    }
  }
  if (added == 0)
    return;
  // the arrays' entries followed by the added ones, in one new chunk
  std::vector<double> merged;
  merged.reserve(static_cast<std::size_t>(n_old + added) * width_);
  for (int m = 0; m < n_old; ++m) {
    merged.push_back(partner[i][m]);
    merged.insert(merged.end(), values[i] + m * dnum_, values[i] + (m + 1) * dnum_);
  }
  merged.insert(merged.end(), scratch_.begin(), scratch_.end());
  wheelsim::replace_partners(lmp_, h, i, merged.data(), n_old + added,
                             "fix wheel/active, restoring the contacts of reactivated particles");
}

void FrozenContacts::sync(int frozen_bit) {
  if (history_ == nullptr || dnum_ == 0)
    return;
  LAMMPS_NS::Atom *atom = lmp_->atom;
  const int *mask = atom->mask;
  FixContactHistory &h = *history_;
  int *npartner = h.*HistoryAccess::npartner();
  int **partner = h.*HistoryAccess::partner();
  double **values = h.*HistoryAccess::values();
  std::vector<double> back; // entries to put back into the arrays
  auto partner_frozen = [&](int tag) {
    const int j = atom->map(tag);
    // A partner not known here cannot be in this rank's list: keep its entry (both frozen
    // particles have not moved, so it cannot have come into reach).
    return j < 0 || (mask[j] & frozen_bit) != 0;
  };
  int max_entries = 0;
  for (int i = 0; i < atom->nlocal; ++i) {
    std::vector<double> &kept = kept_[i];
    if (!(mask[i] & frozen_bit)) {
      // active: every kept pair is computed again
      if (!kept.empty()) {
        put_back(i, kept.data(), static_cast<int>(kept.size()) / width_);
        kept.clear();
      }
      continue;
    }
    // frozen: kept pairs whose partner became active go back; the arrays' pairs whose partner
    // is frozen (now excluded) are kept
    back.clear();
    std::size_t out = 0;
    for (std::size_t e = 0; e < kept.size(); e += width_) {
      if (partner_frozen(static_cast<int>(kept[e]))) {
        if (out != e)
          std::copy(kept.begin() + e, kept.begin() + e + width_, kept.begin() + out);
        out += width_;
      } else {
        back.insert(back.end(), kept.begin() + e, kept.begin() + e + width_);
      }
    }
    kept.resize(out);
    for (int m = 0; m < npartner[i]; ++m) {
      const int tag = partner[i][m];
      if (!partner_frozen(tag))
        continue;
      bool present = false;
      for (std::size_t e = 0; e < kept.size() && !present; e += width_)
        present = static_cast<int>(kept[e]) == tag;
      if (present)
        continue;
      kept.push_back(tag);
      kept.insert(kept.end(), values[i] + m * dnum_, values[i] + (m + 1) * dnum_);
    }
    if (!back.empty())
      put_back(i, back.data(), static_cast<int>(back.size()) / width_);
    max_entries = std::max(max_entries, static_cast<int>(kept.size()) / width_);
  }
  // room in the exchange buffer for a migrating particle's kept entries
  lmp_->comm->maxexchange_fix = std::max(lmp_->comm->maxexchange_fix, 2 + max_entries * width_);
}

long FrozenContacts::kept_local() const {
  long n = 0;
  if (width_ == 0)
    return 0;
  for (int i = 0; i < lmp_->atom->nlocal; ++i)
    n += static_cast<long>(kept_[i].size()) / width_;
  return n;
}

int FrozenContacts::pack(int i, double *buf) const {
  const std::vector<double> &kept = kept_[i];
  buf[0] = width_ > 0 ? static_cast<double>(kept.size() / width_) : 0.0;
  buf[1] = width_;
  std::copy(kept.begin(), kept.end(), buf + 2);
  return 2 + static_cast<int>(kept.size());
}

int FrozenContacts::unpack(int i, const double *buf) {
  const int n = static_cast<int>(buf[0]);
  const int width = static_cast<int>(buf[1]);
  if (n > 0 && width_ != 0 && width != width_)
    lmp_->error->one(FLERR, "fix wheel/active: kept contact histories have another number of "
                            "values than this run's contact model (was the pair style changed "
                            "since the restart file was written?)");
  if (n > 0)
    width_ = width;
  kept_[i].assign(buf + 2, buf + 2 + n * width);
  return 2 + n * width;
}

int FrozenContacts::packed_size(int i) const { return 2 + static_cast<int>(kept_[i].size()); }

int FrozenContacts::max_packed_size_local() const {
  int m = 2;
  for (int i = 0; i < lmp_->atom->nlocal; ++i)
    m = std::max(m, packed_size(i));
  return m;
}

} // namespace wheelsim
