// See fix_tile_history.h.
#include "fix_tile_history.h"

#include "atom.h"
#include "comm.h"
#include "contact_history_access.h"
#include "domain.h"
#include "error.h"
#include "fix_contact_history.h"
#include "fix_output.h"
#include "force.h"
#include "modify.h"
#include "pair.h"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

namespace {

// (block ID, copy number) as one key; copy numbers are small (|k| < 2^19 tiles)
constexpr int kPackHead = 7; // per-grain exchange record before its entries

std::int64_t copy_key(int block_tag, long copy) {
  return (static_cast<std::int64_t>(block_tag) << 20) | static_cast<std::int64_t>(copy + (1 << 19));
}

// Every rank's `mine`, concatenated in rank order, on every rank.
template <typename T>
std::vector<T> gather_all(const std::vector<T> &mine, MPI_Datatype type, MPI_Comm world) {
  int nprocs = 1;
  MPI_Comm_size(world, &nprocs);
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(nprocs), offsets(nprocs, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  for (int r = 1; r < nprocs; ++r)
    offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<T> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(mine.data(), n, type, all.data(), counts.data(), offsets.data(), type, world);
  return all;
}

} // namespace

FixTileHistory::FixTileHistory(LAMMPS *lmp, int narg, char **arg)
    : Fix(lmp, narg, arg), history_(nullptr), block_length_(0.0), width_(0), remapped_(false),
      check_pending_(false), carried_width_(0), vector_{0.0, 0.0, 0.0, 0.0, 0.0} {
  if (narg != 5 || std::strcmp(arg[3], "block") != 0)
    bad_argument("expected 'fix ID group wheelsim/tile_history block L' (L: the settled block's "
                 "periodic length in x [m])");
  if (!wheelsim::parse_finite(arg[4], block_length_) || block_length_ <= 0.0)
    bad_argument("keyword 'block' expects the block's periodic length in x, a length > 0 [m], "
                 "got '%s'",
                 arg[4]);
  if (!domain->xperiodic)
    bad_argument("the block must be periodic in x when the fix is created (it records the "
                 "settled block before 'replicate')");
  history_ = static_cast<FixContactHistory *>(modify->find_fix_style_strict("contacthistory", 0));
  if (history_ == nullptr)
    bad_argument("no pair contact history to carry: the pair style keeps none (a granular pair "
                 "style with 'tangential history', run at least once before this fix); for a "
                 "soil without it tile a bed with -var tile_history 0");
  width_ = 1 + history_->get_dnum();

  vector_flag = 1;
  size_vector = 5;
  global_freq = 1;
  extvector = 0;
  // create_attribute stays 0: LIGGGHTS 3.8's replicate calls set_arrays() on every grain of
  // such fixes after the copy, which would erase the records (grains created later, which
  // have no record anyway, get zeroed slots from grow_arrays)

  grow_arrays(atom->nmax);
  atom->add_callback(0);
  record();
}

FixTileHistory::~FixTileHistory() { atom->delete_callback(id, 0); }

void FixTileHistory::bad_argument(const char *fmt, ...) {
  va_list args;
  va_start(args, fmt);
  wheelsim::fix_argument_error(error, this, fmt, args);
}

void FixTileHistory::record() {
  // the pair list holds the newest histories: copy them into the partner arrays first (what
  // write_restart does; a no-op if they are current already)
  history_->setup_pre_exchange();
  using A = wheelsim::ContactHistoryAccess;
  FixContactHistory &h = *history_;
  const int *npartner = h.*A::npartner();
  int **partner = h.*A::partner();
  double **values = h.*A::values();
  const int dnum = width_ - 1;
  const int nlocal = atom->nlocal;
  // the per-atom values of every fix property/atom (the primitive walls' contact histories among
  // them): replicate resets them to their defaults in the copies and the originals alike
  carried_.clear();
  carried_width_ = 0;
  for (int f = 0; f < modify->nfix; ++f) {
    Fix *fix = modify->fix[f];
    if (std::strcmp(fix->style, "property/atom") != 0 || !fix->peratom_flag)
      continue;
    const int cols = fix->size_peratom_cols == 0 ? 1 : fix->size_peratom_cols;
    carried_.push_back({fix->id, cols});
    carried_width_ += cols;
  }
  carried_values_.assign(static_cast<std::size_t>(atom->nmax) * carried_width_, 0.0);
  std::vector<int> tags;
  std::vector<double> xs;
  int max_entries = 0;
  for (int i = 0; i < nlocal; ++i) {
    if (!(atom->mask[i] & groupbit))
      continue;
    block_tag_[i] = atom->tag[i];
    block_x_[i] = atom->x[i][0];
    std::copy(atom->f[i], atom->f[i] + 3, block_f_[i].begin());
    carry(i, true);
    std::vector<double> &e = entries_[i];
    e.clear();
    for (int m = 0; m < npartner[i]; ++m) {
      e.push_back(partner[i][m]);
      e.insert(e.end(), values[i] + m * dnum, values[i] + (m + 1) * dnum);
    }
    max_entries = std::max(max_entries, npartner[i]);
    tags.push_back(atom->tag[i]);
    xs.push_back(atom->x[i][0]);
  }
  comm->maxexchange_fix =
      std::max(comm->maxexchange_fix, kPackHead + carried_width_ + max_entries * width_);
  // every block grain's x on every rank
  const std::vector<int> all_tags = gather_all(tags, MPI_INT, world);
  const std::vector<double> all_x = gather_all(xs, MPI_DOUBLE, world);
  const int total = static_cast<int>(all_tags.size());
  block_x_of_tag_.clear();
  block_x_of_tag_.reserve(static_cast<std::size_t>(total));
  for (int k = 0; k < total; ++k)
    block_x_of_tag_[all_tags[k]] = all_x[k];
  if (static_cast<int>(block_x_of_tag_.size()) != total)
    error->all(FLERR, "fix wheelsim/tile_history: grain IDs of the block are not unique");
}

void FixTileHistory::carry(int i, bool save) {
  double *v = &carried_values_[static_cast<std::size_t>(i) * carried_width_];
  for (const Carried &c : carried_) {
    const int f = modify->find_fix(c.id.c_str());
    if (f < 0) // per atom: error->one, since a rank without atoms never gets here
      error->one(FLERR, ("fix wheelsim/tile_history: fix " + c.id +
                         " (property/atom) was deleted between the record and the remap")
                            .c_str());
    Fix *fix = modify->fix[f];
    for (int k = 0; k < c.cols; ++k) {
      double &value =
          c.cols == 1 && fix->size_peratom_cols == 0 ? fix->vector_atom[i] : fix->array_atom[i][k];
      if (save)
        v[k] = value;
      else
        value = v[k];
    }
    v += c.cols;
  }
}

int FixTileHistory::modify_param(int narg, char **arg) {
  if (std::strcmp(arg[0], "remap") != 0)
    return 0;
  const bool keep = narg >= 2 && std::strcmp(arg[1], "keep") == 0;
  if (narg < 2 || (!keep && std::strcmp(arg[1], "drop") != 0))
    bad_argument("fix_modify keyword 'remap' expects 'keep' (carry the block's contact histories "
                 "into the tiled bed) or 'drop' (every grain-grain contact starts from zero)");
  if (remapped_)
    bad_argument("fix_modify remap: the histories were remapped already (once per fix)");
  remap(keep);
  return 2;
}

void FixTileHistory::remap(bool keep) {
  const int nlocal = atom->nlocal;
  const double L = block_length_;
  // this rank's grains: (block ID, copy number) -> ID now
  std::vector<int> mine; // triples: block ID, copy, ID
  std::vector<long> copy_of(nlocal, 0);
  long unrecorded = 0;
  for (int i = 0; i < nlocal; ++i) {
    if (!(atom->mask[i] & groupbit))
      continue;
    if (block_tag_[i] == 0) {
      ++unrecorded;
      continue;
    }
    copy_of[i] = std::lround((atom->x[i][0] - block_x_[i]) / L);
    mine.insert(mine.end(), {block_tag_[i], static_cast<int>(copy_of[i]), atom->tag[i]});
  }
  long unrecorded_all = 0;
  MPI_Allreduce(&unrecorded, &unrecorded_all, 1, MPI_LONG, MPI_SUM, world);
  if (unrecorded_all > 0) {
    char msg[256];
    snprintf(msg, sizeof(msg),
             "fix wheelsim/tile_history: %ld grains of the group have no record from the block "
             "(created after the fix, or not copied with their records by 'replicate')",
             unrecorded_all);
    error->all(FLERR, msg);
  }
  const std::vector<int> all = gather_all(mine, MPI_INT, world);
  const int total = static_cast<int>(all.size());
  std::unordered_map<std::int64_t, int> id_of_copy;
  id_of_copy.reserve(static_cast<std::size_t>(total / 3));
  std::vector<int> ids;
  ids.reserve(static_cast<std::size_t>(total / 3));
  for (int k = 0; k < total; k += 3) {
    if (!id_of_copy.emplace(copy_key(all[k], all[k + 1]), all[k + 2]).second)
      error->all(FLERR, "fix wheelsim/tile_history: two grains are the same copy of one block "
                        "grain (was the block periodic with the length given to 'block'?)");
    ids.push_back(all[k + 2]);
  }
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end())
    error->all(FLERR, "fix wheelsim/tile_history: grain IDs repeat (on more than one rank "
                      "'replicate' gives repeated IDs): renumber them first, e.g. with "
                      "delete_atoms (compress yes), then remap");

  // rewrite every recorded grain's partner arrays
  long kept = 0, across = 0, dropped = 0;
  std::vector<double> out;
  for (int i = 0; i < nlocal; ++i) {
    if (!(atom->mask[i] & groupbit))
      continue;
    const std::vector<double> &e = entries_[i];
    const long dropped_before = dropped;
    out.clear();
    const double xi = atom->x[i][0];
    for (std::size_t m = 0; m < e.size(); m += width_) {
      const int p = static_cast<int>(e[m]);
      const auto xp = block_x_of_tag_.find(p);
      if (xp == block_x_of_tag_.end()) {
        ++dropped; // partner outside the group
        continue;
      }
      long best = copy_of[i];
      double best_d = HUGE_VAL;
      for (long c = copy_of[i] - 1; c <= copy_of[i] + 1; ++c) {
        const double d = std::fabs(xi - (xp->second + c * L));
        if (d < best_d) {
          best_d = d;
          best = c;
        }
      }
      const auto id = id_of_copy.find(copy_key(p, best));
      if (id == id_of_copy.end()) {
        ++dropped; // that copy was cut at the bin's end planes
        continue;
      }
      out.push_back(id->second);
      out.insert(out.end(), e.begin() + m + 1, e.begin() + m + width_);
      ++kept;
      if (best != copy_of[i])
        ++across;
    }
    if (keep)
      carry(i, false); // the walls' histories and other per-atom properties, as in the block
    // a grain that kept every contact of the block feels the block's force (checked at the
    // next set-up)
    complete_[i] = dropped == dropped_before ? 1 : 0;
    if (!keep)
      out.clear();
    wheelsim::replace_partners(lmp, *history_, i, out.data(), static_cast<int>(out.size()) / width_,
                               "fix wheelsim/tile_history");
  }
  // the partner arrays are now newer than the pair list: the next run's set-up must not copy
  // the (stale) list over them
  int dim = 0;
  Pair *pair = force->pair_match("gran", 0);
  int *computeflag = pair ? static_cast<int *>(pair->extract("computeflag", dim)) : nullptr;
  if (computeflag == nullptr)
    error->all(FLERR, "fix wheelsim/tile_history: the granular pair style's computeflag was not "
                      "found");
  *computeflag = 0;

  long local[4] = {static_cast<long>(mine.size() / 3), kept, across, dropped},
       sum[4] = {0, 0, 0, 0};
  MPI_Allreduce(local, sum, 4, MPI_LONG, MPI_SUM, world);
  for (int k = 0; k < 4; ++k)
    vector_[k] = static_cast<double>(sum[k]);
  char line[320];
  if (keep)
    snprintf(line, sizeof(line),
             "fix wheelsim/tile_history: %ld grains remapped; %ld contact-history entries kept "
             "(%ld across the block's seam), %ld dropped (partner cut or outside the group)\n",
             sum[0], sum[1], sum[2], sum[3]);
  else
    snprintf(line, sizeof(line),
             "fix wheelsim/tile_history: remap drop: the contact histories of %ld grains "
             "cleared (%ld entries of the block)\n",
             sum[0], sum[1] + sum[3]);
  wheelsim::print_line(lmp, comm->me, line);

  remapped_ = true;
  check_pending_ = true;
  block_x_of_tag_.clear();
}

void FixTileHistory::setup(int /*vflag*/) {
  if (!check_pending_)
    return;
  check_pending_ = false;
  // the forces of this set-up against the block's last forces, over the grains that kept every
  // contact (no partner cut); no grain touches the new end walls (those were cut)
  double local[3] = {0.0, 0.0, 0.0}; // max |df|, sum |df|^2, grains
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(atom->mask[i] & groupbit) || !complete_[i])
      continue;
    const double *f = atom->f[i];
    const std::array<double, 3> &f0 = block_f_[i];
    const double df2 = (f[0] - f0[0]) * (f[0] - f0[0]) + (f[1] - f0[1]) * (f[1] - f0[1]) +
                       (f[2] - f0[2]) * (f[2] - f0[2]);
    local[0] = std::max(local[0], std::sqrt(df2));
    local[1] += df2;
    local[2] += 1.0;
  }
  double max_df = 0.0, sums[2] = {0.0, 0.0};
  MPI_Allreduce(&local[0], &max_df, 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(&local[1], sums, 2, MPI_DOUBLE, MPI_SUM, world);
  vector_[4] = sums[1] > 0.0 ? std::sqrt(sums[0] / sums[1]) : 0.0;
  char line[320];
  snprintf(line, sizeof(line),
           "fix wheelsim/tile_history: force check over %.0f grains that kept every contact of "
           "the block: |f - f_block| rms %.3g N, max %.3g N\n",
           sums[1], vector_[4], max_df);
  wheelsim::print_line(lmp, comm->me, line);
  // the records are no longer needed
  for (std::vector<double> &e : entries_)
    std::vector<double>().swap(e);
}

double FixTileHistory::compute_vector(int i) { return (i >= 0 && i < 5) ? vector_[i] : 0.0; }

double FixTileHistory::memory_usage() {
  double bytes =
      static_cast<double>(block_tag_.capacity()) * (sizeof(int) + 4 * sizeof(double) + 1) +
      static_cast<double>(carried_values_.capacity()) * sizeof(double);
  for (const std::vector<double> &e : entries_)
    bytes += static_cast<double>(e.capacity()) * sizeof(double);
  return bytes + static_cast<double>(block_x_of_tag_.size()) * (sizeof(int) + sizeof(double));
}

void FixTileHistory::grow_arrays(int nmax) {
  block_tag_.resize(nmax, 0);
  block_x_.resize(nmax, 0.0);
  block_f_.resize(nmax, {0.0, 0.0, 0.0});
  complete_.resize(nmax, 0);
  entries_.resize(nmax);
  carried_values_.resize(static_cast<std::size_t>(nmax) * carried_width_, 0.0);
}

void FixTileHistory::copy_arrays(int i, int j, int /*delflag*/) {
  block_tag_[j] = block_tag_[i];
  block_x_[j] = block_x_[i];
  block_f_[j] = block_f_[i];
  complete_[j] = complete_[i];
  entries_[j] = entries_[i];
  std::copy_n(&carried_values_[static_cast<std::size_t>(i) * carried_width_], carried_width_,
              &carried_values_[static_cast<std::size_t>(j) * carried_width_]);
}

void FixTileHistory::set_arrays(int i) {
  block_tag_[i] = 0;
  block_x_[i] = 0.0;
  block_f_[i] = {0.0, 0.0, 0.0};
  complete_[i] = 0;
  entries_[i].clear();
  std::fill_n(&carried_values_[static_cast<std::size_t>(i) * carried_width_], carried_width_, 0.0);
}

// [block ID, x, f (3), complete, n, carried values (carried_width_), entries (n)]
int FixTileHistory::pack_exchange(int i, double *buf) {
  buf[0] = block_tag_[i];
  buf[1] = block_x_[i];
  std::copy(block_f_[i].begin(), block_f_[i].end(), buf + 2);
  buf[5] = complete_[i];
  buf[6] = static_cast<double>(entries_[i].size());
  std::copy_n(&carried_values_[static_cast<std::size_t>(i) * carried_width_], carried_width_,
              buf + kPackHead);
  std::copy(entries_[i].begin(), entries_[i].end(), buf + kPackHead + carried_width_);
  return kPackHead + carried_width_ + static_cast<int>(entries_[i].size());
}

int FixTileHistory::unpack_exchange(int nlocal, double *buf) {
  block_tag_[nlocal] = static_cast<int>(buf[0]);
  block_x_[nlocal] = buf[1];
  std::copy(buf + 2, buf + 5, block_f_[nlocal].begin());
  complete_[nlocal] = static_cast<char>(buf[5]);
  const int n = static_cast<int>(buf[6]);
  std::copy_n(buf + kPackHead, carried_width_,
              &carried_values_[static_cast<std::size_t>(nlocal) * carried_width_]);
  const double *entries = buf + kPackHead + carried_width_;
  entries_[nlocal].assign(entries, entries + n);
  return kPackHead + carried_width_ + n;
}
