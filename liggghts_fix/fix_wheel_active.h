/* fix wheel/active — only the soil near the wheel moves (the "active domain").

   fix ID group-ID wheel/active wheel WHEEL-FIX-ID [keyword value ...]

   Particles of the group whose centre is farther than `distance` from the wheel's bounding sphere
   (the wheel of fix wheel/cosim WHEEL-FIX-ID) are frozen: they keep their position, their
   velocity and angular velocity are zero, the forces on them are discarded, and the pair forces
   between two frozen particles are not computed (they are left out of LIGGGHTS' neighbour list
   through the group ID_frozen, `neigh_modify exclude group ID_frozen ID_frozen`); pairs of a
   frozen and an active particle are computed as usual, so the frozen soil is a rigid boundary of
   the active one. The active set is updated whenever LIGGGHTS rebuilds its neighbour lists (and
   the fix forces a rebuild once the wheel centre has moved `travel` since the last update); the
   contact histories of the excluded pairs are kept and restored when the pair is computed again
   (frozen_contacts.h). Full syntax, defaults, outputs, restart behaviour:
   docs/fix-wheel-active.md.

   Global vector (4): 1 active particles of the group, 2 frozen particles, 3 contact histories
   of frozen-frozen pairs kept by the fix, 4 active-set updates since the fix was created.

   The FixStyle block is in the form LIGGGHTS' Make.sh expects (docs/building.md). */

#ifdef FIX_CLASS

// The style name is stringified (#key): clang-format must not space the slash.
// clang-format off
FixStyle(wheel/active,FixWheelActive)
// clang-format on

#else

#ifndef LMP_FIX_WHEEL_ACTIVE_H
#define LMP_FIX_WHEEL_ACTIVE_H

#include "fix.h"

#include <memory>
#include <string>

namespace wheelsim {
class FrozenContacts;
}

namespace LAMMPS_NS {

class FixWheelCosim;

class FixWheelActive : public Fix {
public:
  FixWheelActive(class LAMMPS *lmp, int narg, char **arg);
  ~FixWheelActive() override;

  int setmask() override;
  void init() override;
  void setup(int vflag) override;
  void setup_pre_exchange() override;
  void setup_pre_neighbor() override;
  void pre_exchange() override;
  void pre_neighbor() override;
  void pre_initial_integrate() override;
  void pre_final_integrate() override;
  void end_of_step() override;
  void post_run() override;

  double compute_vector(int i) override;

  // global state (the wheel centre of the last update) in restart files
  void write_restart(FILE *fp) override;
  void restart(char *buf) override;

  // per-atom kept contact histories (follow atoms between ranks and into restart files)
  double memory_usage() override;
  void grow_arrays(int nmax) override;
  void copy_arrays(int i, int j, int delflag) override;
  void set_arrays(int i) override;
  int pack_exchange(int i, double *buf) override;
  int unpack_exchange(int nlocal, double *buf) override;
  int pack_restart(int i, double *buf) override;
  void unpack_restart(int nlocal, int nth) override;
  int size_restart(int i) override;
  int maxsize_restart() override;

private:
  void parse_arguments(int narg, char **arg);
  void resolve_distances(); // defaults from the wheel's size
  void update_active_set(); // at rebuilds, before the exchange
  void after_exchange();    // at rebuilds, before the list build
  void hold_frozen();       // zero the motion and the forces of frozen particles
  void count();
  [[noreturn]] void bad_argument(const char *fmt, ...);

  std::string wheel_id_;
  FixWheelCosim *wheel_;
  std::string frozen_group_;
  int frozen_bit_;
  std::string active_group_; // the complement of the frozen group (ID_active)
  int active_bit_;
  bool keep_history_;
  bool skip_frozen_pairs_; // false: frozen pairs still computed (keyword frozen_pairs)
  // lengths [m]; < 0: not given (default from the wheel's size at init)
  double distance_arg_, sinkage_arg_, hysteresis_arg_, travel_arg_;
  double distance_, sinkage_, hysteresis_, travel_;
  double bounding_radius_;
  double update_centre_[3]; // wheel centre at the last update [m]
  bool have_update_;
  std::unique_ptr<wheelsim::FrozenContacts> kept_;
  double vector_[4];
  long updates_;
  // statistics of the current run (post_run)
  long run_steps_, run_updates_, run_forced_;
  double run_active_sum_;
  long wheel_touched_frozen_; // steps x frozen particles with a wheel contact force
  bool reported_setup_;
  bool held_since_setup_; // the set-up's forces on frozen particles discarded
};

} // namespace LAMMPS_NS

#endif
#endif
