/* fix wheel/cosim — the rigid lugged wheel's particle contacts, inside LIGGGHTS.

   fix ID group-ID wheel/cosim mesh FILE type T [keyword value ...]

   Every particle of the group that touches the wheel mesh gets a contact force from wheelsim's
   contact law (liggghts_fix/contact: the models of contact/model_list.h, e.g. hertz or eepa
   with history tangential, sjkr cohesion, epsd2 or cdt rolling friction), found against a
   spatial index of the mesh built once in the wheel frame; each step only the particles on a
   candidate list (those that can reach the wheel before LIGGGHTS' next neighbour-list build or
   before the wheel has moved a skin) are looked at (keyword candidates). The wheel moves by a
   motion source (prescribed, or coupled to wheel-rig over ZeroMQ). Full syntax, outputs and restart
   behaviour: docs/fix-wheel-cosim.md.

   Global vector (11): 1-3 contact force on the wheel [N], 4-6 contact torque on the wheel about
   its centre [N m], 7 number of particle-wheel contacts, 8-10 wheel centre [m], 11 = 1 once a
   coupled rig has finished (else 0). World frame.
   Per-atom array (3 columns): contact force of the wheel on each particle [N].

   The FixStyle block is in the form LIGGGHTS' Make.sh expects (docs/building.md). */

#ifdef FIX_CLASS

// The style name is stringified (#key): clang-format must not space the slash.
// clang-format off
FixStyle(wheel/cosim,FixWheelCosim)
// clang-format on

#else

#ifndef LMP_FIX_WHEEL_COSIM_H
#define LMP_FIX_WHEEL_COSIM_H

#include "fix.h"

#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace wheelsim {
struct WheelCosimState; // all non-LIGGGHTS state (Eigen, mesh index, contact law, motion)
struct ContactPass;     // one step's wheel frame and wrench sums (fix_wheel_cosim.cpp)
} // namespace wheelsim

namespace LAMMPS_NS {

class FixWheelCosim : public Fix {
public:
  FixWheelCosim(class LAMMPS *lmp, int narg, char **arg);
  ~FixWheelCosim() override;

  int setmask() override;
  void init() override;
  void setup(int vflag) override;
  void post_force(int vflag) override;
  void end_of_step() override;
  void post_run() override; // prints the fix's wall time and candidate-list use (benchmarks)
  void reset_dt() override;

  double compute_vector(int i) override;
  int min_type() override { return wheel_type_; }
  int max_type() override { return wheel_type_; }

  // For other styles that follow the wheel (fix wheel/active): the wheel centre [m] (world frame)
  // of the last computed step, and the radius [m] of the mesh's bounding sphere about it.
  void wheel_centre(double centre_m[3]) const;
  double bounding_radius() const;

  // per-atom contact history (follows atoms between ranks and into restart files)
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

  // global state (wheel pose and twist) in restart files
  void write_restart(FILE *fp) override;
  void restart(char *buf) override;

private:
  void parse_arguments(int narg, char **arg);
  void read_materials();
  void check_timestep(bool set_up); // set_up: the first init or a new dt (errors only)
  void compute_contacts(bool update_history);
  void contact_particle(int i, wheelsim::ContactPass &pass); // one owned particle
  // The candidate list (docs/fix-wheel-cosim.md, "Candidate list")
  bool candidates_exact() const; // the neighbour settings bound the particles' travel
  bool candidates_stale() const;
  void build_candidates();
  void clear_history_outside_candidates();
  void report_candidates(); // post_run: list size and builds of the run
  void write_vtk();
  void schedule_checkpoint(long step); // the rig asked for one: reneighbour at that step
  void write_checkpoint();             // restart file + .wheel + .info at the current step
  void write_wheel_state(const std::string &path); // histories, pose, wrench (collective)
  void read_wheel_state(const std::string &path);  // keyword 'resume'

  void report_wrench();                                       // to the motion source
  [[noreturn]] void coupling_failed(const std::exception &e); // error->one on rank 0
  [[noreturn]] void bad_argument(const char *fmt, ...);
  // The same for a condition this rank may meet alone (wheelsim::fix_local_error): never a
  // barrier the other ranks do not reach.
  [[noreturn]] void bad_local_argument(const char *fmt, ...);

  std::unique_ptr<wheelsim::WheelCosimState> s_;
  int wheel_type_;
  int nslots_;             // history slots per particle
  int history_columns_;    // nslots_ * kSlotDoubles
  double **history_;       // per atom: nslots_ slots of kSlotDoubles doubles
  double **contact_force_; // per atom: force of the wheel on the particle [N]
  double vector_[11];      // the global vector, reduced over ranks
  bool first_setup_;       // warn about initial overlaps only once
};

} // namespace LAMMPS_NS

#endif
#endif
