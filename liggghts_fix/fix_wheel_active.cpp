// fix wheel/active: see fix_wheel_active.h and docs/fix-wheel-active.md.
#include "fix_wheel_active.h"

#include "fix_output.h"
#include "fix_wheel_cosim.h"
#include "frozen_contacts.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_contact_history.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

/// Defaults, as fractions of the wheel's bounding radius R (docs/fix-wheel-active.md): the
/// sinkage allowance z = R/4, the distance 0.5 R + 2 z (= R with the default z), the hysteresis
/// and the wheel travel between forced updates a tenth of the distance each.
constexpr double kDefaultSinkagePerRadius = 0.25;
constexpr double kDistanceRadiusPart = 0.5;
constexpr double kDistanceSinkageFactor = 2.0;
constexpr double kDefaultHysteresisPerDistance = 0.1;
constexpr double kDefaultTravelPerDistance = 0.1;

} // namespace

/* ---------------------------------------------------------------------- */

FixWheelActive::FixWheelActive(LAMMPS *lmp, int narg, char **arg)
    : Fix(lmp, narg, arg), wheel_(nullptr), frozen_bit_(0), active_bit_(0), keep_history_(true),
      skip_frozen_pairs_(true), distance_arg_(-1.0), sinkage_arg_(-1.0), hysteresis_arg_(-1.0),
      travel_arg_(-1.0), distance_(0.0), sinkage_(0.0), hysteresis_(0.0), travel_(0.0),
      bounding_radius_(0.0), update_centre_{0.0, 0.0, 0.0}, have_update_(false),
      kept_(new wheelsim::FrozenContacts(lmp)), vector_{0.0, 0.0, 0.0, 0.0}, updates_(0),
      run_steps_(0), run_updates_(0), run_forced_(0), run_active_sum_(0.0),
      wheel_touched_frozen_(0), reported_setup_(false), held_since_setup_(false) {
  if (!atom->radius_flag || !atom->omega_flag || !atom->torque_flag)
    error->fix_error(
        FLERR, this,
        "needs per-atom radius, omega and torque: use atom_style granular (or sphere)");
  parse_arguments(narg, arg);

  // The frozen particles are a group (also usable in the deck, e.g. to dump only the active
  // soil). A group found after read_restart keeps its members from the file; a new one starts
  // with `member` (0 or 1) for every local particle. Returns its bit.
  auto find_or_create_group = [&](const std::string &name, int member) {
    int igroup = group->find(name.c_str());
    if (igroup < 0) {
      std::vector<int> flags(std::max(atom->nlocal, 1), member);
      group->create(const_cast<char *>(name.c_str()), flags.data());
      igroup = group->find(name.c_str());
    }
    return group->bitmask[igroup];
  };
  frozen_group_ = std::string(id) + "_frozen";
  frozen_bit_ = find_or_create_group(frozen_group_, 0);
  // Its complement, ID_active (every particle not frozen), for the deck's per-particle fixes:
  // gravity, walls and the integrator on ID_active skip the frozen soil (docs/fix-wheel-active.md
  // "Active group"). A new one starts with every particle.
  active_group_ = std::string(id) + "_active";
  active_bit_ = find_or_create_group(active_group_, 1);
  // Pairs of two frozen particles are left out of the neighbour lists from the next build on.
  if (skip_frozen_pairs_) {
    std::vector<char> name(frozen_group_.begin(), frozen_group_.end());
    name.push_back('\0');
    char exclude[] = "exclude", group_kw[] = "group";
    char *args[4] = {exclude, group_kw, name.data(), name.data()};
    neighbor->modify_params(4, args);
  }

  vector_flag = 1;
  size_vector = 4;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  force_reneighbor = 1;
  next_reneighbor = -1;
  nevery = 1;

  grow_arrays(atom->nmax);
  atom->add_callback(0);
  atom->add_callback(1);
}

FixWheelActive::~FixWheelActive() {
  // Without the fix nobody holds the frozen particles: make every particle active again (the
  // ghost masks follow at the next neighbour-list build). The contact histories this fix kept
  // are dropped (docs/fix-wheel-active.md, "Restrictions").
  const int inverse = ~frozen_bit_;
  for (int i = 0; i < atom->nlocal; ++i)
    atom->mask[i] = (atom->mask[i] & inverse) | active_bit_;
  atom->delete_callback(id, 0);
  atom->delete_callback(id, 1);
}

void FixWheelActive::bad_argument(const char *fmt, ...) {
  va_list args;
  va_start(args, fmt);
  wheelsim::fix_argument_error(error, this, fmt, args);
}

void FixWheelActive::parse_arguments(int narg, char **arg) {
  if (narg < 5 || std::strcmp(arg[3], "wheel") != 0)
    bad_argument("expected 'fix ID group wheel/active wheel WHEEL-FIX-ID [keyword value ...]' "
                 "(WHEEL-FIX-ID: the ID of a fix wheel/cosim)");
  wheel_id_ = arg[4];
  auto length = [&](int iarg, const char *what, bool zero_ok) {
    if (iarg + 1 >= narg)
      bad_argument("keyword '%s' expects %s", arg[iarg], what);
    double value = 0.0;
    if (!wheelsim::parse_finite(arg[iarg + 1], value) || value < 0.0 || (!zero_ok && value == 0.0))
      bad_argument("keyword '%s' expects %s, got '%s'", arg[iarg], what, arg[iarg + 1]);
    return value;
  };
  int iarg = 5;
  while (iarg < narg) {
    const char *key = arg[iarg];
    if (std::strcmp(key, "distance") == 0) {
      distance_arg_ =
          length(iarg,
                 "a length > 0 [m] (how far beyond the wheel's bounding sphere the soil "
                 "moves)",
                 false);
    } else if (std::strcmp(key, "sinkage") == 0) {
      sinkage_arg_ = length(iarg, "a length >= 0 [m] (the sinkage allowance)", true);
    } else if (std::strcmp(key, "hysteresis") == 0) {
      hysteresis_arg_ = length(iarg, "a length >= 0 [m]", true);
    } else if (std::strcmp(key, "travel") == 0) {
      travel_arg_ = length(iarg, "a length > 0 [m] (wheel-centre travel between updates)", false);
    } else if (std::strcmp(key, "frozen_pairs") == 0) {
      if (iarg + 1 >= narg)
        bad_argument("keyword 'frozen_pairs' expects skip or compute");
      if (std::strcmp(arg[iarg + 1], "skip") == 0)
        skip_frozen_pairs_ = true;
      else if (std::strcmp(arg[iarg + 1], "compute") == 0)
        skip_frozen_pairs_ = false;
      else
        bad_argument("keyword 'frozen_pairs' expects skip (the speed-up) or compute (frozen "
                     "particles only held still: the reference of the tests), got '%s'",
                     arg[iarg + 1]);
    } else if (std::strcmp(key, "history") == 0) {
      if (iarg + 1 >= narg)
        bad_argument("keyword 'history' expects keep or drop");
      if (std::strcmp(arg[iarg + 1], "keep") == 0)
        keep_history_ = true;
      else if (std::strcmp(arg[iarg + 1], "drop") == 0)
        keep_history_ = false;
      else
        bad_argument("keyword 'history' expects keep (restore the contact history of pairs of "
                     "frozen particles) or drop, got '%s'",
                     arg[iarg + 1]);
    } else {
      bad_argument("unknown keyword '%s'; expected one of distance, sinkage, hysteresis, travel, "
                   "history, frozen_pairs",
                   key);
    }
    iarg += 2;
  }
  if (distance_arg_ > 0.0 && sinkage_arg_ >= 0.0)
    bad_argument("keywords 'distance' and 'sinkage' exclude each other: 'sinkage' only sets the "
                 "default distance (0.5 R + 2 sinkage)");
}

int FixWheelActive::setmask() {
  return PRE_EXCHANGE | PRE_NEIGHBOR | PRE_INITIAL_INTEGRATE | PRE_FINAL_INTEGRATE | END_OF_STEP;
}

/* ---------------------------------------------------------------------- */

void FixWheelActive::init() {
  Fix *fix = modify->find_fix_id(wheel_id_.c_str());
  if (fix == nullptr || std::strcmp(fix->style, "wheel/cosim") != 0)
    bad_argument("keyword 'wheel' expects the ID of a fix wheel/cosim, got '%s'%s",
                 wheel_id_.c_str(), fix ? " (a fix of another style)" : " (no fix with that ID)");
  wheel_ = static_cast<FixWheelCosim *>(fix);
  for (int k = 0; k < modify->nfix; ++k)
    if (modify->fix[k] != this && std::strcmp(modify->fix[k]->style, style) == 0)
      bad_argument("only one fix wheel/active per run (also '%s'): a particle frozen by one "
                   "would not move near the other's wheel",
                   modify->fix[k]->id);
  if (modify->find_fix_style("multisphere", 0) != nullptr)
    bad_argument("multisphere particles are not supported (a frozen sphere of a clump would "
                 "stop only itself); use single spheres");
  if (atom->map_style == 0)
    bad_argument("needs an atom map to find contact partners: put 'atom_modify map array' "
                 "before the box is created or the restart read");
  resolve_distances();

  FixContactHistory *history =
      static_cast<FixContactHistory *>(modify->find_fix_style_strict("contacthistory", 0));
  if (!kept_->bind(keep_history_ ? history : nullptr))
    bad_argument("the contact histories kept in the restart file have another number of values "
                 "than the pair style's (%d): the contact model must not change across a "
                 "restart",
                 history ? history->get_dnum() : 0);
}

void FixWheelActive::resolve_distances() {
  bounding_radius_ = wheel_->bounding_radius();
  sinkage_ = sinkage_arg_ >= 0.0 ? sinkage_arg_ : kDefaultSinkagePerRadius * bounding_radius_;
  distance_ = distance_arg_ > 0.0
                  ? distance_arg_
                  : kDistanceRadiusPart * bounding_radius_ + kDistanceSinkageFactor * sinkage_;
  hysteresis_ =
      hysteresis_arg_ >= 0.0 ? hysteresis_arg_ : kDefaultHysteresisPerDistance * distance_;
  travel_ = travel_arg_ > 0.0 ? travel_arg_ : kDefaultTravelPerDistance * distance_;
  if (travel_ >= distance_)
    bad_argument("keyword 'travel' (%g m) must be smaller than the distance (%g m): the wheel "
                 "would reach frozen soil before the next update",
                 travel_, distance_);
  if (!reported_setup_) {
    char line[640];
    // The sinkage the domain allows for: the one given or defaulted, or for a distance given,
    // the sinkage whose default distance it is. wheel-cosim records it in the run file
    // (/parameters/liggghts/active_sinkage_allowance) and wheelsim-post warns when the wheel
    // sinks deeper (docs/fix-wheel-active.md "Sinkage allowance").
    const double allowance =
        distance_arg_ > 0.0 ? std::max(0.0, (distance_ - kDistanceRadiusPart * bounding_radius_) /
                                                kDistanceSinkageFactor)
                            : sinkage_;
    snprintf(line, sizeof(line),
             "fix wheel/active %s: wheel %s (bounding radius %.4g m); particles of group %s "
             "farther than %.4g m from its centre are frozen (distance %.4g m%s + radius; "
             "sinkage allowance %.4g m%s), active again within %.4g m; updated each time the "
             "wheel centre has moved %.4g m; pairs of frozen particles: %s\n",
             id, wheel_id_.c_str(), bounding_radius_, group->names[igroup],
             bounding_radius_ + distance_ + hysteresis_, distance_,
             distance_arg_ > 0.0 ? "" : " (default: 0.5 R + 2 x sinkage allowance)", allowance,
             distance_arg_ > 0.0   ? ", the one whose default distance is the distance given"
             : sinkage_arg_ >= 0.0 ? ""
                                   : ", the default R/4",
             bounding_radius_ + distance_, travel_,
             !skip_frozen_pairs_ ? "computed"
             : keep_history_     ? "skipped, contact histories kept"
                                 : "skipped, contact histories dropped");
    wheelsim::print_line(lmp, comm->me, line);
    reported_setup_ = true;
  }
}

/* ----------------------------------------------------------------------
   The active set: updated on neighbour-list rebuilds only (the ones this fix forces), so that
   the list always matches the masks (ghost masks are sent by comm->borders, after
   pre_exchange); the kept histories are synchronised on every rebuild.
------------------------------------------------------------------------- */

void FixWheelActive::setup_pre_exchange() {
  // Only the first set-up of the fix decides the active set; later set-ups (the next run, a
  // run after read_restart, write_restart) keep it, so that a continued or restarted run
  // freezes and reactivates exactly when the uninterrupted one does. If the wheel moved since
  // the last update, setup() forces a rebuild (and so an update) at the first step.
  if (!have_update_)
    update_active_set();
}

void FixWheelActive::pre_exchange() {
  // Only on the rebuilds this fix forced (the wheel moved 'travel' since the last update): the
  // update steps then depend on the wheel's path alone, not on when LIGGGHTS happens to rebuild
  // its lists (which a restart changes), so a restarted run freezes particles at the same steps.
  if (update->ntimestep == next_reneighbor)
    update_active_set();
}

void FixWheelActive::setup_pre_neighbor() { after_exchange(); }

void FixWheelActive::pre_neighbor() { after_exchange(); }

void FixWheelActive::update_active_set() {
  if (wheel_ == nullptr)
    return; // write_restart before the first run: nothing has been frozen yet
  double centre[3];
  wheel_->wheel_centre(centre);
  const double active_r = bounding_radius_ + distance_;
  const double frozen_r = active_r + hysteresis_;
  const double active_r2 = active_r * active_r, frozen_r2 = frozen_r * frozen_r;
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  int *mask = atom->mask;
  const int inverse = ~frozen_bit_;
  for (int i = 0; i < atom->nlocal; ++i) {
    const bool frozen = (mask[i] & frozen_bit_) != 0;
    if (!(mask[i] & groupbit)) {
      if (frozen)
        mask[i] &= inverse;
    } else {
      const double dx = x[i][0] - centre[0], dy = x[i][1] - centre[1], dz = x[i][2] - centre[2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (frozen && d2 <= active_r2) {
        mask[i] &= inverse;
      } else if (!frozen && d2 > frozen_r2) {
        mask[i] |= frozen_bit_;
        v[i][0] = v[i][1] = v[i][2] = 0.0;
        omega[i][0] = omega[i][1] = omega[i][2] = 0.0;
      }
    }
    // ID_active is the complement (ghost masks follow with this rebuild's borders)
    mask[i] = (mask[i] & frozen_bit_) ? (mask[i] & ~active_bit_) : (mask[i] | active_bit_);
  }
  std::copy(centre, centre + 3, update_centre_);
  have_update_ = true;
  ++updates_;
  ++run_updates_;
}

void FixWheelActive::after_exchange() {
  if (wheel_ == nullptr)
    return;
  if (keep_history_ && skip_frozen_pairs_)
    kept_->sync(frozen_bit_);
  count();
}

void FixWheelActive::count() {
  double local[3] = {0.0, 0.0, static_cast<double>(kept_->kept_local())}, total[3];
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & groupbit))
      continue;
    if (mask[i] & frozen_bit_)
      local[1] += 1.0;
    else
      local[0] += 1.0;
  }
  MPI_Allreduce(local, total, 3, MPI_DOUBLE, MPI_SUM, world);
  std::copy(total, total + 3, vector_);
  vector_[3] = static_cast<double>(updates_);
}

/* ----------------------------------------------------------------------
   Frozen particles: no motion, no force
------------------------------------------------------------------------- */

void FixWheelActive::setup(int /*vflag*/) {
  hold_frozen();
  held_since_setup_ = false;
  // A coupled wheel gets its first pose from the rig in its own setup, after our update: if it
  // is elsewhere, update again at the first step.
  double centre[3];
  wheel_->wheel_centre(centre);
  const double dx = centre[0] - update_centre_[0], dy = centre[1] - update_centre_[1],
               dz = centre[2] - update_centre_[2];
  // (a rebuild forced at the end of the previous run is moot: the set was updated just now)
  next_reneighbor = dx * dx + dy * dy + dz * dz > travel_ * travel_ ? update->ntimestep + 1 : -1;
}

void FixWheelActive::pre_initial_integrate() {
  // Forces of the steps are discarded in pre_final_integrate; only those of a run's set-up
  // (other fixes' setup() may add theirs after ours) remain to be discarded, once.
  if (!held_since_setup_) {
    hold_frozen();
    held_since_setup_ = true;
  }
}

void FixWheelActive::pre_final_integrate() {
  // the wheel must never touch a frozen particle: count it (post_run warns)
  const int *mask = atom->mask;
  double **wheel_force = wheel_->array_atom;
  if (wheel_force != nullptr)
    for (int i = 0; i < atom->nlocal; ++i)
      if ((mask[i] & frozen_bit_) &&
          (wheel_force[i][0] != 0.0 || wheel_force[i][1] != 0.0 || wheel_force[i][2] != 0.0))
        ++wheel_touched_frozen_;
  hold_frozen();
}

void FixWheelActive::hold_frozen() {
  // Called after all forces of a step (pre_final_integrate) and once before the first half-step
  // after a set-up (pre_initial_integrate, for the forces of setup): the integrator then adds
  // exactly zero to v and x of a frozen particle.
  const int *mask = atom->mask;
  double **v = atom->v, **omega = atom->omega, **f = atom->f, **torque = atom->torque;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & frozen_bit_))
      continue;
    v[i][0] = v[i][1] = v[i][2] = 0.0;
    omega[i][0] = omega[i][1] = omega[i][2] = 0.0;
    f[i][0] = f[i][1] = f[i][2] = 0.0;
    torque[i][0] = torque[i][1] = torque[i][2] = 0.0;
  }
}

void FixWheelActive::end_of_step() {
  ++run_steps_;
  run_active_sum_ += vector_[0];
  if (!have_update_)
    return;
  double centre[3];
  wheel_->wheel_centre(centre);
  const double dx = centre[0] - update_centre_[0], dy = centre[1] - update_centre_[1],
               dz = centre[2] - update_centre_[2];
  if (dx * dx + dy * dy + dz * dz > travel_ * travel_ && next_reneighbor != update->ntimestep + 1) {
    next_reneighbor = update->ntimestep + 1; // same decision on every rank (same wheel pose)
    ++run_forced_;
  }
}

void FixWheelActive::post_run() {
  long touched = 0;
  MPI_Allreduce(&wheel_touched_frozen_, &touched, 1, MPI_LONG, MPI_SUM, world);
  if (comm->me == 0 && run_steps_ > 0) {
    char line[512];
    const double mean_active = run_active_sum_ / run_steps_;
    const double total = vector_[0] + vector_[1];
    snprintf(line, sizeof(line),
             "fix wheel/active %s: %ld steps, %.1f of %.0f particles active on average (%.1f "
             "%%), now %.0f active, %.0f frozen, %.0f frozen contacts kept; active-set updates "
             "%ld (%ld forced by the wheel moving %.3g m)\n",
             id, run_steps_, mean_active, total, total > 0 ? 100.0 * mean_active / total : 0.0,
             vector_[0], vector_[1], vector_[2], run_updates_, run_forced_, travel_);
    wheelsim::print_line(lmp, comm->me, line);
    if (touched > 0) {
      char msg[400];
      snprintf(msg, sizeof(msg),
               "fix wheel/active %s: the wheel touched frozen particles (%ld particle-steps): "
               "they did not move; increase 'distance' (now %g m)",
               id, touched, distance_);
      error->warning(FLERR, msg);
    }
  }
  run_steps_ = run_updates_ = run_forced_ = 0;
  run_active_sum_ = 0.0;
  wheel_touched_frozen_ = 0;
}

double FixWheelActive::compute_vector(int i) { return vector_[i]; }

/* ----------------------------------------------------------------------
   Global restart state: the wheel centre of the last update of the active set
------------------------------------------------------------------------- */

void FixWheelActive::write_restart(FILE *fp) {
  double list[5] = {1.0, // format version
                    have_update_ ? 1.0 : 0.0, update_centre_[0], update_centre_[1],
                    update_centre_[2]};
  if (comm->me == 0) {
    const int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 5, fp);
  }
}

void FixWheelActive::restart(char *buf) {
  const double *list = reinterpret_cast<const double *>(buf);
  if (list[0] != 1.0)
    bad_argument("restart data of fix wheel/active has format %g, expected 1", list[0]);
  have_update_ = list[1] != 0.0;
  std::copy(list + 2, list + 5, update_centre_);
}

/* ----------------------------------------------------------------------
   Per-atom storage: the kept contact histories
------------------------------------------------------------------------- */

double FixWheelActive::memory_usage() {
  return static_cast<double>(atom->nmax) * sizeof(std::vector<double>) +
         static_cast<double>(kept_->kept_local()) * kept_->entry_width() * sizeof(double);
}

void FixWheelActive::grow_arrays(int nmax) { kept_->grow(nmax); }

void FixWheelActive::copy_arrays(int i, int j, int /*delflag*/) { kept_->copy(i, j); }

void FixWheelActive::set_arrays(int i) {
  // LIGGGHTS calls this for new atoms, and for every atom at the first setup after the fix was
  // created, when setup_pre_neighbor has already taken the histories of frozen pairs out of fix
  // contacthistory (and, after read_restart, when they came from the file). A new atom is never
  // frozen, and an active atom keeps nothing: clear only those.
  if (!(atom->mask[i] & frozen_bit_))
    kept_->clear(i);
}

int FixWheelActive::pack_exchange(int i, double *buf) { return kept_->pack(i, buf); }

int FixWheelActive::unpack_exchange(int nlocal, double *buf) { return kept_->unpack(nlocal, buf); }

int FixWheelActive::pack_restart(int i, double *buf) {
  const int n = kept_->pack(i, buf + 1);
  buf[0] = n + 1;
  return n + 1;
}

void FixWheelActive::unpack_restart(int nlocal, int nth) {
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; ++k)
    m += static_cast<int>(extra[nlocal][m]);
  kept_->unpack(nlocal, &extra[nlocal][m + 1]);
}

int FixWheelActive::size_restart(int i) { return kept_->packed_size(i) + 1; }

int FixWheelActive::maxsize_restart() {
  int local = kept_->max_packed_size_local() + 1, all = 0;
  MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_MAX, world);
  return all;
}
