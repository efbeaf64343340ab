// fix wheel/cosim: see fix_wheel_cosim.h and docs/fix-wheel-cosim.md.
#include "fix_wheel_cosim.h"

#include "contact_law.h"
#include "contact_model.h"
#include "contact_slots.h"
#include "coupled_motion.h"
#include "coupler/protocol.h"
#include "coupler/transport.h"
#include "fix_output.h"
#include "prescribed_motion.h"
#include "wheel_motion.h"
#include "wheel_surface_vtk.h"
#include "wheelsim/geometry/mesh_error.h"
#include "wheelsim/geometry/mesh_io.h"
#include "wheelsim/geometry/sphere_contact_index.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_property_global.h"
#include "force.h"
#include "input.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"
#include "variable.h"
#include "write_restart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace wheelsim {

/// Largest number of contacts one particle can have with the wheel in one step (a sphere in a
/// groove touches at most a few faces; extra contacts are an error in the mesh or the setup).
constexpr int kMaxContactsPerParticle = 8;
constexpr int kDefaultSlots = 3;
/// Time-step check thresholds (docs/fix-wheel-cosim.md): dt must not exceed these fractions of
/// the particles' Rayleigh time and of the Hertz collision time of a particle hitting the wheel.
constexpr double kMaxRayleighFraction = 0.3;
constexpr double kMaxHertzFraction = 0.1;
/// A later `run` of the same deck (a chunked coupled run re-initialises the fix at every chunk)
/// re-checks the Hertz limit with the particles' speeds of that moment: one grain flung faster
/// than any before must not end an hour's run over a rule with a tenfold margin, so there it is a
/// warning, and an error only beyond this factor over the limit (under 5 steps per collision).
constexpr double kMidRunFatalFactor = 2.0;
/// Candidate list: how far a point of the wheel surface may move, in neighbour skins, before the
/// list is rebuilt; and a relative allowance on the list's radius so that round-off in the distance
/// test can never leave out a particle the full scan would test.
constexpr double kWheelTravelPerSkin = 1.0;
constexpr double kCandidateRoundOff = 1e-9;

/// The candidate list (docs/fix-wheel-cosim.md, "Candidate list"): the owned particles of the
/// group that can touch the wheel's surface before the list is rebuilt. A particle is left out
/// only if, at the build, the surface is farther from its centre than its radius + how far it
/// can move + how far any point of the surface may move until the next build (the wheel centre's
/// travel plus bounding radius x rotation angle). Valid until LIGGGHTS rebuilds its neighbour
/// lists (atoms are then migrated and re-sorted, and may have moved half a skin) or the surface
/// may have moved `wheel_travel_m`.
struct CandidateList {
  bool enabled = true;    ///< keyword candidates (no: test every particle each step)
  std::vector<int> atoms; ///< local indices, ascending (the full scan's order)
  LAMMPS_NS::bigint neighbor_builds = -1; ///< neighbor->ncalls at the build; -1: build next use
  int nlocal = -1;                        ///< atom->nlocal at the build
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();       ///< wheel centre at the build [m]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity(); ///< wheel orientation at the build
  double wheel_travel_m = 0.0; ///< how far a surface point may move until a rebuild [m]
  bool clear_pending = false;  ///< the histories of non-candidates are still to be emptied
  bool warned_inexact = false;
  // statistics of the current run (printed by post_run)
  long builds_at_neighbor = 0; ///< builds on a step LIGGGHTS rebuilt its lists
  long builds_between = 0;     ///< builds between those (the wheel had moved)
  double listed_sum = 0.0;     ///< sum over passes of the list size
  long passes = 0;
  long arrived = 0; ///< particles received from other ranks
};

/// One contact pass over the particles: the wheel frame of the step and the wheel's wrench,
/// summed over this rank's particles.
struct ContactPass {
  const WheelPose &state;
  Eigen::Matrix3d R;  ///< wheel frame -> world
  Eigen::Matrix3d Rt; ///< world -> wheel frame
  double bounding_radius_m;
  double dt_s;
  bool update_history;
  bool accumulate_vtk;
  Eigen::Vector3d wheel_force_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d wheel_torque_Nm = Eigen::Vector3d::Zero();
  double ncontacts = 0.0;

  ContactPass(const WheelPose &s, double bounding_m, double dt, bool update, bool vtk)
      : state(s), R(s.q_WB.toRotationMatrix()), Rt(R.transpose()), bounding_radius_m(bounding_m),
        dt_s(dt), update_history(update), accumulate_vtk(vtk) {}
};

struct WheelCosimState {
  std::string mesh_path;
  double scale = 1.0;
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
  std::unique_ptr<geometry::SphereContactIndex> index;
  std::vector<double> triangle_area_m2;

  contact::ContactSettings settings;
  std::vector<contact::PairConstants> pair; // by particle type (index = type)
  std::vector<contact::Material> material;  // by type

  WheelPose state;
  std::int64_t state_step = -1; // the step `state` belongs to
  std::unique_ptr<WheelMotion> motion;
  PrescribedMotion *prescribed = nullptr; // the motion, if prescribed
  CoupledMotion *coupled = nullptr;       // the motion, if coupled
  bool motion_is_coupled = false;
  CoupledMotion::Settings coupled_settings;
  std::array<std::string, 6> motion_args{{"0", "0", "0", "0", "0", "0"}};
  std::array<int, 6> motion_variable{{-1, -1, -1, -1, -1, -1}};
  std::array<double, 6> motion_constant{{0, 0, 0, 0, 0, 0}};

  // Checkpoints (keyword 'checkpoint', docs/coupled-runs.md "Checkpoint and resume"): restart
  // files DIR/liggghts-<step>.restart written at the steps the coupled rig asks for.
  std::string checkpoint_dir;
  std::string inputs_hash = "none";        // recorded beside each restart, compared on resume
  std::vector<long> checkpoint_steps;      // written by this process, oldest first (2 are kept)
  std::string resume_path;                 // keyword 'resume': a checkpoint's wheel state file
  long restored_wrench_step = -1;          // restart format 2: the step of the wrench below
  std::array<double, 7> restored_wrench{}; // global vector 1-7 of that step's post_force
  bool checkpoint_warned = false;          // asked for without 'checkpoint': warned once

  bool check_timestep = true;
  bool timestep_checked = false;      // the first init's check (fatal) is done: later ones may warn
  double timestep_warned_ratio = 1.0; // the largest dt / limit warned of mid-run so far
  int vtk_every = 0;
  std::string vtk_prefix;
  std::unique_ptr<PvdSeries> vtk_series;         // rank 0: PREFIX_<step>.vtk listed in PREFIX.pvd
  std::vector<double> triangle_normal_force_sum; // [N], summed over the VTK window's steps
  std::vector<double> triangle_contact_sum;
  long vtk_window_steps = 0;

  std::vector<geometry::SurfaceContact> contacts;     // query scratch
  long too_many_contacts = 0;                         // contacts dropped (> kMaxContacts...)
  double contact_seconds = 0.0, motion_seconds = 0.0; // wall time in post_force this run
  long timed_steps = 0;
  long slot_overflows = 0; // contacts without a free history slot
  CandidateList candidates;
};

} // namespace wheelsim

namespace {

bool parse_on_off(const char *text, bool &value) {
  if (std::strcmp(text, "on") == 0 || std::strcmp(text, "yes") == 0)
    value = true;
  else if (std::strcmp(text, "off") == 0 || std::strcmp(text, "no") == 0)
    value = false;
  else
    return false;
  return true;
}

} // namespace

/* ---------------------------------------------------------------------- */

FixWheelCosim::FixWheelCosim(LAMMPS *lmp, int narg, char **arg)
    : Fix(lmp, narg, arg), s_(new wheelsim::WheelCosimState), wheel_type_(0),
      nslots_(wheelsim::kDefaultSlots), history_columns_(0), history_(nullptr),
      contact_force_(nullptr), first_setup_(true) {
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->fix_error(FLERR, this,
                     "needs per-atom radius, mass, omega and torque: use atom_style granular "
                     "(or sphere)");
  parse_arguments(narg, arg);
  history_columns_ = nslots_ * wheelsim::kSlotDoubles;

  // Every rank reads the mesh; the ranks agree before any error, since one that cannot (a node
  // without the file system) must not leave the others waiting in fix_error's barrier.
  std::string mesh_error;
  try {
    wheelsim::geometry::LoadOptions options;
    options.scale = s_->scale;
    s_->index = std::make_unique<wheelsim::geometry::SphereContactIndex>(
        wheelsim::geometry::load_mesh(s_->mesh_path, options));
  } catch (const std::exception &e) {
    mesh_error = e.what();
  }
  int loaded_here = mesh_error.empty() ? 1 : 0, loaded_all = 0, loaded_any = 0;
  MPI_Allreduce(&loaded_here, &loaded_all, 1, MPI_INT, MPI_MIN, world);
  MPI_Allreduce(&loaded_here, &loaded_any, 1, MPI_INT, MPI_MAX, world);
  if (!loaded_any)
    bad_argument("keyword 'mesh': %s", mesh_error.c_str());
  if (!loaded_all) {
    if (!loaded_here)
      bad_local_argument("keyword 'mesh': %s (other ranks read it: a file system this rank does "
                         "not see?)",
                         mesh_error.c_str());
    MPI_Barrier(world); // until the rank that failed aborts the run
  }
  const auto &mesh = s_->index->mesh();
  for (const auto &t : mesh.triangles)
    s_->triangle_area_m2.push_back(0.5 * (mesh.vertices_m[t[1]] - mesh.vertices_m[t[0]])
                                             .cross(mesh.vertices_m[t[2]] - mesh.vertices_m[t[0]])
                                             .norm());
  s_->state.p_WB_W = s_->origin_m;

  // The motion source. Components are constants or equal-style variables (resolved in init()).
  std::array<wheelsim::PrescribedMotion::Component, 3> v, w;
  for (int k = 0; k < 6; ++k) {
    auto component = [this, k]() {
      const int ivar = s_->motion_variable[k];
      return ivar >= 0 ? input->variable->compute_equal(ivar) : s_->motion_constant[k];
    };
    (k < 3 ? v[k] : w[k - 3]) = component;
  }
  std::string description = "prescribed: v = (" + s_->motion_args[0] + ", " + s_->motion_args[1] +
                            ", " + s_->motion_args[2] + ") m/s, omega = (" + s_->motion_args[3] +
                            ", " + s_->motion_args[4] + ", " + s_->motion_args[5] + ") rad/s";
  if (s_->motion_is_coupled) {
    auto coupled = std::make_unique<wheelsim::CoupledMotion>(s_->coupled_settings, world);
    s_->coupled = coupled.get();
    s_->motion = std::move(coupled);
  } else {
    auto prescribed = std::make_unique<wheelsim::PrescribedMotion>(v, w, description);
    s_->prescribed = prescribed.get();
    s_->motion = std::move(prescribed);
  }

  if (s_->vtk_every > 0) {
    s_->triangle_normal_force_sum.assign(mesh.triangles.size(), 0.0);
    s_->triangle_contact_sum.assign(mesh.triangles.size(), 0.0);
  }

  vector_flag = 1;
  size_vector = 11;
  global_freq = 1;
  extvector = 0;
  peratom_flag = 1;
  size_peratom_cols = 3;
  peratom_freq = 1;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  if (!s_->checkpoint_dir.empty()) {
    if (!s_->motion_is_coupled)
      bad_argument("keyword 'checkpoint' needs 'motion coupled' (the rig decides when to "
                   "checkpoint; a prescribed run uses LIGGGHTS' own 'restart' command)");
    force_reneighbor = 1; // a checkpoint step rebuilds the neighbour lists (atoms inside the box)
    next_reneighbor = -1;
  }
  nevery = 1;
  std::fill(vector_, vector_ + 11, 0.0);

  grow_arrays(atom->nmax);
  atom->add_callback(0);
  atom->add_callback(1);
  for (int i = 0; i < atom->nlocal; ++i)
    set_arrays(i);
  if (!s_->resume_path.empty())
    read_wheel_state(s_->resume_path);

  if (comm->me == 0) {
    char line[512];
    snprintf(line, sizeof(line),
             "fix wheel/cosim %s: mesh %s, %zu triangles, %zu vertices, bounding radius %.6g m, "
             "index cell %.3g m; %s\n",
             id, s_->mesh_path.c_str(), mesh.triangles.size(), mesh.vertices_m.size(),
             s_->index->bounding_radius_m(), s_->index->cell_size_m(),
             s_->motion->describe().c_str());
    wheelsim::print_line(lmp, comm->me, line);
  }
}

FixWheelCosim::~FixWheelCosim() {
  atom->delete_callback(id, 0);
  atom->delete_callback(id, 1);
  memory->destroy(history_);
  memory->destroy(contact_force_);
}

void FixWheelCosim::bad_argument(const char *fmt, ...) {
  va_list args;
  va_start(args, fmt);
  wheelsim::fix_argument_error(error, this, fmt, args);
}

void FixWheelCosim::bad_local_argument(const char *fmt, ...) {
  va_list args;
  va_start(args, fmt);
  wheelsim::fix_local_error(error, this, fmt, args);
}

void FixWheelCosim::parse_arguments(int narg, char **arg) {
  // Required, in this order: mesh FILE type T
  if (narg < 7 || std::strcmp(arg[3], "mesh") != 0 || std::strcmp(arg[5], "type") != 0)
    bad_argument("expected 'fix ID group wheel/cosim mesh FILE type T [keyword value ...]'");
  s_->mesh_path = arg[4];
  char *end = nullptr;
  const long type = std::strtol(arg[6], &end, 10);
  if (*end != '\0' || type < 1 || type > atom->ntypes)
    bad_argument("keyword 'type' expects the wheel's atom type, an integer in 1..%d (the "
                 "types of create_box), got '%s'",
                 atom->ntypes, arg[6]);
  wheel_type_ = static_cast<int>(type);

  auto need = [&](int iarg, int count, const char *usage) {
    if (iarg + count >= narg)
      bad_argument("keyword '%s' expects %s", arg[iarg], usage);
  };
  auto number = [&](int iarg, const char *keyword, const char *what) {
    double value = 0.0;
    if (!wheelsim::parse_finite(arg[iarg], value))
      bad_argument("keyword '%s' expects %s, got '%s'", keyword, what, arg[iarg]);
    return value;
  };
  auto on_off = [&](int iarg) {
    bool value = false;
    if (!parse_on_off(arg[iarg + 1], value))
      bad_argument("keyword '%s' expects on or off, got '%s'", arg[iarg], arg[iarg + 1]);
    return value;
  };

  // check_timestep is the fix's own on/off keyword; the contact-model keywords and switches
  // come from the model table (liggghts_fix/contact/contact_model.h).
  auto model_kind = [](const char *key, wheelsim::contact::ModelKind &kind) {
    for (wheelsim::contact::ModelKind k : wheelsim::contact::kModelKinds)
      if (std::strcmp(key, wheelsim::contact::kind_keyword(k)) == 0) {
        kind = k;
        return true;
      }
    return false;
  };
  int iarg = 7;
  while (iarg < narg) {
    const char *key = arg[iarg];
    wheelsim::contact::ModelKind kind;
    if (std::strcmp(key, "scale") == 0) {
      need(iarg, 1, "a positive factor (mesh units to m)");
      s_->scale = number(iarg + 1, key, "a positive factor (mesh units to m)");
      if (s_->scale <= 0.0)
        bad_argument("keyword 'scale' expects a factor > 0, got %s", arg[iarg + 1]);
      iarg += 2;
    } else if (std::strcmp(key, "origin") == 0) {
      need(iarg, 3, "three coordinates x y z [m] of the wheel centre");
      for (int k = 0; k < 3; ++k)
        s_->origin_m[k] = number(iarg + 1 + k, key, "a coordinate [m]");
      iarg += 4;
    } else if (model_kind(key, kind)) {
      const std::string names = wheelsim::contact::model_names(kind);
      need(iarg, 1, ("one of " + names).c_str());
      const wheelsim::contact::ModelEntry *model =
          wheelsim::contact::find_model(kind, arg[iarg + 1]);
      if (model == nullptr)
        bad_argument("keyword '%s' expects one of %s, got '%s'", key, names.c_str(), arg[iarg + 1]);
      wheelsim::contact::select_model(s_->settings, *model);
      iarg += 2;
    } else if (const wheelsim::contact::SwitchSpec *sw = wheelsim::contact::find_switch(key)) {
      need(iarg, 1, "on or off");
      sw->set(s_->settings, on_off(iarg));
      iarg += 2;
    } else if (std::strcmp(key, "check_timestep") == 0) {
      need(iarg, 1, "on or off");
      s_->check_timestep = on_off(iarg);
      iarg += 2;
    } else if (std::strcmp(key, "motion") == 0) {
      need(iarg, 1, "prescribed vx vy vz wx wy wz");
      if (std::strcmp(arg[iarg + 1], "prescribed") == 0) {
        need(iarg + 1, 6, "six values vx vy vz [m/s] wx wy wz [rad/s], each a number or v_name");
        for (int k = 0; k < 6; ++k) {
          const char *value = arg[iarg + 2 + k];
          s_->motion_args[k] = value;
          if (std::strncmp(value, "v_", 2) != 0)
            s_->motion_constant[k] = number(iarg + 2 + k, "motion prescribed",
                                            "a number or an equal-style variable v_name");
        }
        iarg += 8;
      } else if (std::strcmp(arg[iarg + 1], "coupled") == 0) {
        need(iarg + 1, 1, "an endpoint (ipc://PATH or tcp://127.0.0.1:PORT) after 'coupled'");
        s_->motion_is_coupled = true;
        s_->coupled_settings.endpoint = arg[iarg + 2];
        // Checked here, at the fix command, not when the coupling starts after settling: an
        // ipc path longer than the system's socket-path limit used to fail at the first
        // coupled step, minutes into the run.
        try {
          wheelsim::coupler::normalize_connect_endpoint(s_->coupled_settings.endpoint);
        } catch (const std::exception &e) {
          bad_argument("motion coupled: %s", e.what());
        }
        iarg += 3;
        // optional sub-keywords of 'motion coupled'
        while (iarg + 1 < narg) {
          if (std::strcmp(arg[iarg], "timeout") == 0) {
            const double t = number(iarg + 1, "motion coupled timeout", "a time > 0 [s]");
            if (t <= 0.0)
              bad_argument("motion coupled: 'timeout' expects a time > 0 s, got %s", arg[iarg + 1]);
            s_->coupled_settings.step_timeout_s = t;
            s_->coupled_settings.handshake_timeout_s = std::max(t, 60.0);
          } else if (std::strcmp(arg[iarg], "exchange_every") == 0) {
            const double n = number(iarg + 1, "motion coupled exchange_every", "an integer >= 1");
            if (n < 1 || n != std::floor(n))
              bad_argument("motion coupled: 'exchange_every' expects an integer >= 1, got %s",
                           arg[iarg + 1]);
            s_->coupled_settings.exchange_every = static_cast<int>(n);
          } else {
            break;
          }
          iarg += 2;
        }
        continue;
      } else {
        bad_argument("keyword 'motion' expects 'prescribed' or 'coupled', got '%s'", arg[iarg + 1]);
      }
    } else if (std::strcmp(key, "vtk") == 0) {
      need(iarg, 2,
           "N PREFIX (write the wheel surface every N steps to PREFIX_<step>.vtk; N = 0: off)");
      const double every = number(iarg + 1, key, "a step interval N >= 0 (0: off)");
      if (every < 0 || every != std::floor(every))
        bad_argument("keyword 'vtk' expects a step interval N >= 0 (0: off), got '%s'",
                     arg[iarg + 1]);
      s_->vtk_every = static_cast<int>(every);
      s_->vtk_prefix = arg[iarg + 2];
      iarg += 3;
    } else if (std::strcmp(key, "candidates") == 0) {
      need(iarg, 1, "yes or no");
      if (std::strcmp(arg[iarg + 1], "yes") == 0)
        s_->candidates.enabled = true;
      else if (std::strcmp(arg[iarg + 1], "no") == 0)
        s_->candidates.enabled = false;
      else
        bad_argument("keyword 'candidates' expects yes (keep a list of the particles near the "
                     "wheel) or no (test every particle each step), got '%s'",
                     arg[iarg + 1]);
      iarg += 2;
    } else if (std::strcmp(key, "checkpoint") == 0) {
      need(iarg, 1, "a directory for the checkpoint restart files");
      s_->checkpoint_dir = arg[iarg + 1];
      iarg += 2;
    } else if (std::strcmp(key, "resume") == 0) {
      need(iarg, 1, "the wheel state file of a checkpoint (DIR/liggghts-STEP.restart.wheel)");
      s_->resume_path = arg[iarg + 1];
      iarg += 2;
    } else if (std::strcmp(key, "inputs_hash") == 0) {
      need(iarg, 1, "a word identifying the run's inputs (scripts/wheel-cosim passes a sha256)");
      s_->inputs_hash = arg[iarg + 1];
      iarg += 2;
    } else if (std::strcmp(key, "slots") == 0) {
      need(iarg, 1, "the number of contact-history slots per particle, 2..4");
      const double n = number(iarg + 1, key, "an integer 2..4");
      if (n < 2 || n > 4 || n != std::floor(n))
        bad_argument("keyword 'slots' expects an integer 2..4, got '%s'", arg[iarg + 1]);
      nslots_ = static_cast<int>(n);
      iarg += 2;
    } else {
      std::string models;
      for (wheelsim::contact::ModelKind k : wheelsim::contact::kModelKinds)
        models += std::string(wheelsim::contact::kind_keyword(k)) + ", ";
      bad_argument("unknown keyword '%s'; expected one of scale, origin, %s%s, motion, vtk, "
                   "slots, candidates, check_timestep, checkpoint, inputs_hash, resume",
                   key, models.c_str(), wheelsim::contact::switch_keywords().c_str());
    }
  }
}

int FixWheelCosim::setmask() { return POST_FORCE | END_OF_STEP; }

/* ---------------------------------------------------------------------- */

void FixWheelCosim::init() {
  for (int k = 0; k < 6; ++k) {
    const std::string &text = s_->motion_args[k];
    if (text.compare(0, 2, "v_") != 0)
      continue;
    std::string name = text.substr(2);
    const int ivar = input->variable->find(&name[0]);
    if (ivar < 0)
      bad_argument("motion prescribed: variable '%s' does not exist", name.c_str());
    if (!input->variable->equalstyle(ivar))
      bad_argument("motion prescribed: variable '%s' must be equal-style", name.c_str());
    s_->motion_variable[k] = ivar;
  }
  read_materials();
  // A run resumed from a checkpoint ('resume') was set up by the run it continues: its first
  // init is checked as a later run's, with the grains' speeds at the checkpoint.
  if (s_->check_timestep)
    check_timestep(!s_->timestep_checked && s_->resume_path.empty());
  s_->timestep_checked = true;
}

void FixWheelCosim::read_materials() {
  const int ntypes = atom->ntypes;
  auto find = [&](const char *name, const char *kind, int len1, int len2) {
    Fix *fix = modify->find_fix_property(name, "property/global", kind, len1, len2, style, false);
    if (fix == nullptr)
      bad_argument("material property '%s' is missing or too short: it must be given with 'fix "
                   "ID all property/global %s %s ...' for all %d atom types, including the "
                   "wheel's type %d",
                   name, name, kind, ntypes, wheel_type_);
    return static_cast<FixPropertyGlobal *>(fix);
  };
  // The properties the selected contact models read (each model declares its own in
  // liggghts_fix/contact/models/*.h), from the arrays of fix property/global.
  namespace wc = wheelsim::contact;
  const std::vector<const wc::PropertySpec *> properties = wc::required_properties(s_->settings);
  std::vector<FixPropertyGlobal *> fixes;
  for (const wc::PropertySpec *p : properties) {
    const bool per_type = p->style == wc::PropertyStyle::PerType;
    const bool scalar = p->style == wc::PropertyStyle::Scalar;
    fixes.push_back(find(p->name, wc::style_keyword(p->style), scalar ? 0 : ntypes,
                         per_type || scalar ? 0 : ntypes));
  }

  s_->material.assign(ntypes + 1, {});
  for (std::size_t k = 0; k < properties.size(); ++k)
    if (properties[k]->material)
      for (int t = 1; t <= ntypes; ++t)
        s_->material[t].*(properties[k]->material) = fixes[k]->compute_vector(t - 1);
  s_->pair.assign(ntypes + 1, {});
  const int w = wheel_type_ - 1;
  for (int t = 1; t <= ntypes; ++t) {
    wc::PairMaterial pm;
    for (std::size_t k = 0; k < properties.size(); ++k) {
      const wc::PropertySpec &p = *properties[k];
      if (p.style == wc::PropertyStyle::PerTypePair)
        pm.*(p.pair) = fixes[k]->compute_array(t - 1, w);
      else if (p.style == wc::PropertyStyle::Scalar)
        pm.*(p.pair) = fixes[k]->compute_scalar();
    }
    try {
      s_->pair[t] =
          wc::makePairConstants(s_->material[t], s_->material[wheel_type_], pm, s_->settings);
    } catch (const std::exception &ex) {
      bad_argument("materials of particle type %d against the wheel's type %d: %s", t, wheel_type_,
                   ex.what());
    }
  }
}

void FixWheelCosim::check_timestep(bool set_up) {
  // Smallest radius, largest speed and the density of each type in the group (over all ranks).
  const int ntypes = atom->ntypes;
  std::vector<double> rmin(ntypes + 1, 1e300), rho(ntypes + 1, 0.0), mass_at_rmin(ntypes + 1, 0);
  double vmax = 0.0;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(atom->mask[i] & groupbit))
      continue;
    const int t = atom->type[i];
    const double *v = atom->v[i];
    vmax = std::max(vmax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    if (atom->radius[i] < rmin[t]) {
      rmin[t] = atom->radius[i];
      mass_at_rmin[t] = atom->rmass[i];
      rho[t] = atom->rmass[i] / (4.0 / 3.0 * M_PI * std::pow(atom->radius[i], 3));
    }
  }
  std::vector<double> rmin_all(ntypes + 1), rho_all(ntypes + 1), mass_all(ntypes + 1);
  MPI_Allreduce(rmin.data(), rmin_all.data(), ntypes + 1, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(rho.data(), rho_all.data(), ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(mass_at_rmin.data(), mass_all.data(), ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  double vmax_all = 0.0;
  MPI_Allreduce(&vmax, &vmax_all, 1, MPI_DOUBLE, MPI_MAX, world);
  // The wheel's twist: prescribed values now, or the last known state when coupled.
  const Eigen::Vector3d vw = s_->prescribed ? s_->prescribed->velocity_m_s() : s_->state.v_WB_W;
  const Eigen::Vector3d ww =
      s_->prescribed ? s_->prescribed->angular_velocity_rad_s() : s_->state.w_WB_W;
  const double v_impact =
      std::max(vmax_all + vw.norm() + ww.norm() * s_->index->bounding_radius_m(),
               1e-3); // a resting bed still needs a finite impact speed for the Hertz estimate
  const double dt = update->dt;
  for (int t = 1; t <= ntypes; ++t) {
    if (rmin_all[t] > 1e299 || t == wheel_type_)
      continue;
    const auto &m = s_->material[t];
    const double G = m.youngsModulus / (2.0 * (1.0 + m.poissonsRatio));
    const double rayleigh =
        M_PI * rmin_all[t] * std::sqrt(rho_all[t] / G) / (0.1631 * m.poissonsRatio + 0.8766);
    const double Yeff = s_->pair[t].Yeff;
    const double hertz =
        2.87 * std::pow(mass_all[t] * mass_all[t] / (rmin_all[t] * Yeff * Yeff * v_impact), 0.2);
    // The selected models' own limits (e.g. eepa's damping), then the fix's general one.
    for (const wheelsim::contact::ModelEntry *model :
         wheelsim::contact::selected_models(s_->settings)) {
      if (model->spec->timestep == nullptr)
        continue;
      const double max_dt = model->spec->timestep(s_->pair[t], rmin_all[t], mass_all[t]);
      if (dt > max_dt) {
        char msg[768];
        snprintf(msg, sizeof(msg),
                 "time step %g s is too large for '%s %s' with particle type %d (radius %g m, "
                 "mass %g kg): %s; use timestep <= %g s or 'check_timestep off'",
                 dt, wheelsim::contact::kind_keyword(model->kind), model->spec->name, t,
                 rmin_all[t], mass_all[t], model->spec->timestepRule, max_dt);
        error->fix_error(FLERR, this, msg);
      }
    }
    const double max_dt =
        std::min(wheelsim::kMaxRayleighFraction * rayleigh, wheelsim::kMaxHertzFraction * hertz);
    if (dt <= max_dt)
      continue;
    char msg[640];
    snprintf(msg, sizeof(msg),
             "time step %g s is too large for the wheel contact of particle type %d (radius "
             "%g m): it must be <= %.2g x Rayleigh time %g s and <= %.2g x Hertz time %g s "
             "(impact speed %g m/s); use timestep <= %g or 'check_timestep off'",
             dt, t, rmin_all[t], wheelsim::kMaxRayleighFraction, rayleigh,
             wheelsim::kMaxHertzFraction, hertz, v_impact, max_dt);
    // Mid-run only the Hertz limit can newly fail (the fastest particle's speed): a warning each
    // time the excess grows, an error beyond kMidRunFatalFactor (docs/fix-wheel-cosim.md).
    const double ratio = dt / max_dt;
    if (set_up || ratio > wheelsim::kMidRunFatalFactor ||
        dt > wheelsim::kMaxRayleighFraction * rayleigh)
      error->fix_error(FLERR, this, msg);
    if (ratio > s_->timestep_warned_ratio) {
      s_->timestep_warned_ratio = ratio;
      char warn[800];
      snprintf(warn, sizeof(warn),
               "fix wheel/cosim %s at step %ld, during the run: %s (%.3gx the limit: a warning "
               "up to %gx; the run goes on)",
               id, static_cast<long>(update->ntimestep), msg, ratio, wheelsim::kMidRunFatalFactor);
      error->warning(FLERR, warn);
    }
  }
}

/* ---------------------------------------------------------------------- */

void FixWheelCosim::setup(int /*vflag*/) {
  if (s_->prescribed) {
    s_->state.v_WB_W = s_->prescribed->velocity_m_s();
    s_->state.w_WB_W = s_->prescribed->angular_velocity_rad_s();
  } else if (!s_->coupled->connected() && !s_->coupled->rig_finished()) {
    try {
      s_->state = s_->coupled->connect(s_->state, update->ntimestep, update->dt);
    } catch (const std::exception &e) {
      coupling_failed(e);
    }
  }
  s_->state_step = update->ntimestep;
  s_->candidates.neighbor_builds = -1; // atoms may have been added, moved or deleted since
  if (s_->candidates.enabled && !candidates_exact() && !s_->candidates.warned_inexact &&
      comm->me == 0) {
    char msg[400];
    snprintf(msg, sizeof(msg),
             "fix wheel/cosim %s: the candidate list needs neighbour lists checked every step "
             "('neigh_modify delay 0 every 1'; now delay %d every %d%s): testing every particle "
             "each step instead",
             id, neighbor->delay, neighbor->every, neighbor->build_once ? " once yes" : "");
    error->warning(FLERR, msg);
    s_->candidates.warned_inexact = true;
  }
  compute_contacts(false);
  if (s_->restored_wrench_step == update->ntimestep) {
    // A run restarted from a checkpoint: the rig gets the wrench the stopped run computed in this
    // step's post_force, as the uninterrupted run sent it (setup's own is computed from the
    // end-of-step velocities: damping forces differ).
    std::copy(s_->restored_wrench.begin(), s_->restored_wrench.end(), vector_);
    s_->restored_wrench_step = -1;
  }
  report_wrench(); // the first exchange step's wrench (later setups: already sent)
  if (first_setup_) {
    first_setup_ = false;
    // Particles already overlapping the wheel when the first run starts get a kick.
    int overlapping = 0;
    for (int i = 0; i < atom->nlocal; ++i)
      if (contact_force_[i][0] != 0.0 || contact_force_[i][1] != 0.0 || contact_force_[i][2] != 0.0)
        ++overlapping;
    int total = 0;
    MPI_Allreduce(&overlapping, &total, 1, MPI_INT, MPI_SUM, world);
    if (total > 0 && comm->me == 0) {
      char msg[256];
      snprintf(msg, sizeof(msg),
               "fix wheel/cosim %s: %d particles overlap the wheel at the start: place the wheel "
               "(keyword 'origin') above the bed, or lower it in gradually",
               id, total);
      error->warning(FLERR, msg);
    }
  }
  if (s_->vtk_every > 0 && update->ntimestep % s_->vtk_every == 0)
    write_vtk();
}

void FixWheelCosim::post_force(int /*vflag*/) {
  // The pose of this step is asked for as late as possible: a coupled rig computes it while
  // LIGGGHTS integrated the particles and computed the pair forces.
  const double t0 = MPI_Wtime();
  if (update->ntimestep > s_->state_step) {
    try {
      s_->state = s_->motion->next_state(s_->state, update->ntimestep, update->dt);
    } catch (const std::exception &e) {
      coupling_failed(e);
    }
    s_->state_step = update->ntimestep;
    if (s_->coupled && s_->coupled->checkpoint_step() > update->ntimestep)
      schedule_checkpoint(s_->coupled->checkpoint_step());
  }
  const double t1 = MPI_Wtime();
  compute_contacts(update->setupflag == 0);
  s_->motion_seconds += t1 - t0;
  s_->contact_seconds += MPI_Wtime() - t1;
  ++s_->timed_steps;
}

void FixWheelCosim::post_run() {
  // The fix's own cost, for benchmarks: wall time in the contact loop (incl. the wrench
  // reduction) and in the motion source (waiting for the rig when coupled), slowest rank.
  double local[2] = {s_->contact_seconds, s_->motion_seconds}, slowest[2];
  MPI_Reduce(local, slowest, 2, MPI_DOUBLE, MPI_MAX, 0, world);
  if (comm->me == 0 && s_->timed_steps > 0) {
    char line[256];
    snprintf(line, sizeof(line),
             "fix wheel/cosim %s: %ld steps, contacts %.4g s (%.1f us/step), motion %.4g s "
             "(%.1f us/step)\n",
             id, s_->timed_steps, slowest[0], 1e6 * slowest[0] / s_->timed_steps, slowest[1],
             1e6 * slowest[1] / s_->timed_steps);
    wheelsim::print_line(lmp, comm->me, line);
  }
  s_->contact_seconds = s_->motion_seconds = 0.0;
  s_->timed_steps = 0;
  report_candidates();
}

void FixWheelCosim::report_candidates() {
  // How much the candidate list saved, and how often it was rebuilt (rank 0's builds: every
  // rank rebuilds at the same steps unless its particle count changed on its own).
  wheelsim::CandidateList &list = s_->candidates;
  double local[2] = {list.listed_sum, static_cast<double>(list.arrived)}, total[2];
  MPI_Reduce(local, total, 2, MPI_DOUBLE, MPI_SUM, 0, world);
  if (comm->me == 0 && list.enabled && list.passes > 0) {
    char line[400];
    snprintf(line, sizeof(line),
             "fix wheel/cosim %s: candidate list: %.1f of %.0f particles tested per step (all "
             "ranks); list builds: %ld with LIGGGHTS' neighbour lists, %ld in between (wheel "
             "surface moved > %.3g m); %.0f particles arrived from other ranks\n",
             id, total[0] / list.passes, static_cast<double>(atom->natoms), list.builds_at_neighbor,
             list.builds_between, list.wheel_travel_m, total[1]);
    wheelsim::print_line(lmp, comm->me, line);
  }
  list.listed_sum = 0.0;
  list.passes = list.builds_at_neighbor = list.builds_between = list.arrived = 0;
}

void FixWheelCosim::end_of_step() {
  if (s_->coupled && s_->coupled->checkpoint_step() == update->ntimestep) {
    if (!s_->checkpoint_dir.empty())
      write_checkpoint(); // before this step's Wrench: the rig then knows the restart exists
    s_->coupled->checkpoint_done();
  }
  report_wrench();
  if (s_->vtk_every > 0 && update->ntimestep % s_->vtk_every == 0)
    write_vtk();
}

void FixWheelCosim::report_wrench() {
  wheelsim::WheelWrench wrench;
  wrench.f_B_W = Eigen::Vector3d(vector_[0], vector_[1], vector_[2]);
  wrench.t_B_W = Eigen::Vector3d(vector_[3], vector_[4], vector_[5]);
  try {
    s_->motion->wrench_computed(update->ntimestep, update->get_cur_time(), wrench,
                                static_cast<long>(vector_[6]));
  } catch (const std::exception &e) {
    coupling_failed(e);
  }
}

void FixWheelCosim::coupling_failed(const std::exception &e) {
  // Seen on rank 0 only (it alone talks to the rig): a one-rank error, which ends all ranks.
  char msg[1024];
  snprintf(msg, sizeof(msg), "fix wheel/cosim %s: coupling with the rig failed at step %ld: %s", id,
           static_cast<long>(update->ntimestep), e.what());
  error->one(FLERR, msg);
  std::abort(); // not reached: error->one ends the run
}

void FixWheelCosim::reset_dt() {
  if (s_->check_timestep)
    check_timestep(true); // a new time step is a new set-up
}

/* ----------------------------------------------------------------------
   The contact loop: every owned particle of the group near the wheel, in the wheel frame.
------------------------------------------------------------------------- */

void FixWheelCosim::compute_contacts(bool update_history) {
  wheelsim::ContactPass pass(s_->state, s_->index->bounding_radius_m(), update->dt, update_history,
                             update_history && s_->vtk_every > 0);
  wheelsim::CandidateList &list = s_->candidates;
  if (list.enabled && candidates_exact()) {
    if (candidates_stale())
      build_candidates();
    if (update_history && list.clear_pending)
      clear_history_outside_candidates();
    for (const int i : list.atoms)
      contact_particle(i, pass);
    list.listed_sum += static_cast<double>(list.atoms.size());
    ++list.passes;
  } else {
    for (int i = 0; i < atom->nlocal; ++i)
      contact_particle(i, pass);
  }
  if (pass.accumulate_vtk)
    ++s_->vtk_window_steps;

  const Eigen::Vector3d &centre = s_->state.p_WB_W;
  double local[7] = {pass.wheel_force_N.x(),
                     pass.wheel_force_N.y(),
                     pass.wheel_force_N.z(),
                     pass.wheel_torque_Nm.x(),
                     pass.wheel_torque_Nm.y(),
                     pass.wheel_torque_Nm.z(),
                     pass.ncontacts};
  double total[7];
  MPI_Allreduce(local, total, 7, MPI_DOUBLE, MPI_SUM, world);
  std::copy(total, total + 7, vector_);
  vector_[7] = centre.x();
  vector_[8] = centre.y();
  vector_[9] = centre.z();
  vector_[10] = s_->coupled && s_->coupled->rig_finished() ? 1.0 : 0.0;
}

void FixWheelCosim::contact_particle(int i, wheelsim::ContactPass &pass) {
  using Eigen::Vector3d;
  double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega,
         **torque = atom->torque;
  const double r = atom->radius[i];
  const wheelsim::WheelPose &state = pass.state;
  const Vector3d &centre = state.p_WB_W;

  contact_force_[i][0] = contact_force_[i][1] = contact_force_[i][2] = 0.0;
  if (!(atom->mask[i] & groupbit))
    return;
  auto *slots = reinterpret_cast<wheelsim::ContactSlot *>(history_[i]);
  const Vector3d xi(x[i][0], x[i][1], x[i][2]);
  const Vector3d d = xi - centre;
  const double reach = pass.bounding_radius_m;
  if (d.squaredNorm() > (reach + r) * (reach + r)) {
    if (pass.update_history)
      wheelsim::clear_contact_slots(slots, nslots_);
    return;
  }
  s_->contacts.clear();
  int n = s_->index->find_contacts(pass.Rt * d, r, s_->contacts);
  if (n == 0) {
    if (pass.update_history)
      wheelsim::clear_contact_slots(slots, nslots_);
    return;
  }
  if (n > wheelsim::kMaxContactsPerParticle) {
    s_->too_many_contacts += n - wheelsim::kMaxContactsPerParticle;
    n = wheelsim::kMaxContactsPerParticle;
  }
  wheelsim::SlotQuery queries[wheelsim::kMaxContactsPerParticle];
  int slot_of[wheelsim::kMaxContactsPerParticle];
  for (int j = 0; j < n; ++j)
    queries[j] = {s_->contacts[j].feature_key, s_->contacts[j].point_m};
  wheelsim::match_contact_slots(slots, nslots_, queries, n, r, pass.update_history, slot_of);

  const Vector3d vi(v[i][0], v[i][1], v[i][2]);
  const Vector3d wi(omega[i][0], omega[i][1], omega[i][2]);
  Vector3d force_on_particle = Vector3d::Zero(), torque_on_particle = Vector3d::Zero();
  for (int j = 0; j < n; ++j) {
    const wheelsim::geometry::SurfaceContact &c = s_->contacts[j];
    const Vector3d normal = pass.R * c.normal;
    const Vector3d point = centre + pass.R * c.point_m;
    wheelsim::contact::ContactState cs;
    cs.radius = r;
    cs.mass = atom->rmass[i];
    cs.overlap = c.overlap_m;
    cs.normal = normal;
    cs.vRel = wheelsim::contact::relativeContactVelocity(vi, wi, state.velocity_at(point), normal,
                                                         r, c.overlap_m);
    cs.omega = wi;
    cs.omegaSurface = state.w_WB_W;
    wheelsim::contact::ContactHistory fresh{};
    wheelsim::contact::ContactHistory &history =
        slot_of[j] >= 0 ? slots[slot_of[j]].history : fresh;
    if (slot_of[j] < 0 && pass.update_history)
      ++s_->slot_overflows;
    const wheelsim::contact::ContactResult res = wheelsim::contact::evaluate(
        s_->pair[atom->type[i]], cs, pass.dt_s, pass.update_history, history);
    force_on_particle += res.force;
    torque_on_particle += res.torque;
    // Reaction on the wheel: -F at the contact point, and minus the rolling-resistance torque
    // (the particle's torque less the moment of its tangential force about its centre).
    const Vector3d tangential = res.force - res.force.dot(normal) * normal;
    const Vector3d lever_torque = -(r - 0.5 * c.overlap_m) * normal.cross(tangential);
    const Vector3d rolling_torque = res.torque - lever_torque;
    pass.wheel_force_N -= res.force;
    pass.wheel_torque_Nm += (point - centre).cross(-res.force) - rolling_torque;
    pass.ncontacts += 1.0;
    if (pass.accumulate_vtk) {
      s_->triangle_normal_force_sum[c.triangle] += res.force.dot(normal);
      s_->triangle_contact_sum[c.triangle] += 1.0;
    }
  }
  for (int k = 0; k < 3; ++k) {
    f[i][k] += force_on_particle[k];
    torque[i][k] += torque_on_particle[k];
    contact_force_[i][k] = force_on_particle[k];
  }
}

/* ----------------------------------------------------------------------
   The candidate list (wheelsim::CandidateList)
------------------------------------------------------------------------- */

bool FixWheelCosim::candidates_exact() const {
  // LIGGGHTS checks every step whether a particle has moved half a skin since its lists were
  // built (centre displacement plus radius growth, when radii vary) and rebuilds them if so. With
  // a delay, a coarser check interval or 'once yes', particles can move further unnoticed.
  return neighbor->every == 1 && neighbor->delay == 0 && !neighbor->build_once;
}

bool FixWheelCosim::candidates_stale() const {
  const wheelsim::CandidateList &list = s_->candidates;
  if (neighbor->ncalls != list.neighbor_builds || atom->nlocal != list.nlocal)
    return true;
  // How far a point of the surface can have moved since the build: the centre's travel plus
  // the bounding radius times the rotation angle (an arc is no longer than radius x angle).
  const double angle_rad = s_->state.q_WB.angularDistance(list.q_WB);
  const double travel_m =
      (s_->state.p_WB_W - list.centre_m).norm() + s_->index->bounding_radius_m() * angle_rad;
  return travel_m > list.wheel_travel_m;
}

void FixWheelCosim::build_candidates() {
  wheelsim::CandidateList &list = s_->candidates;
  const double skin_m = neighbor->skin;
  // How far a particle can move (plus how much its radius can grow) until the next build: half a
  // skin from where LIGGGHTS built its lists; from anywhere in between, up to another half skin
  // on top (another skin when radii vary: LIGGGHTS then lets the centre move further while the
  // radius shrinks).
  const bool at_neighbor_build = neighbor->ago == 0;
  const double particle_travel_m =
      at_neighbor_build ? 0.5 * skin_m : (atom->radvary_flag ? 2.0 : 1.0) * skin_m;
  list.wheel_travel_m = wheelsim::kWheelTravelPerSkin * skin_m;
  list.centre_m = s_->state.p_WB_W;
  list.q_WB = s_->state.q_WB;
  const Eigen::Matrix3d R_BW = list.q_WB.toRotationMatrix().transpose(); // W -> wheel frame
  const double margin_m = particle_travel_m + list.wheel_travel_m;
  const double reach_m = s_->index->bounding_radius_m() + margin_m;

  double **x = atom->x;
  const double *radius = atom->radius;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  list.atoms.clear();
  for (int i = 0; i < nlocal; ++i) {
    contact_force_[i][0] = contact_force_[i][1] = contact_force_[i][2] = 0.0;
    if (!(mask[i] & groupbit))
      continue;
    const Eigen::Vector3d d(x[i][0] - list.centre_m.x(), x[i][1] - list.centre_m.y(),
                            x[i][2] - list.centre_m.z());
    const double listed_m = (reach_m + radius[i]) * (1.0 + wheelsim::kCandidateRoundOff);
    if (d.squaredNorm() > listed_m * listed_m)
      continue; // cheap reject: outside the bounding sphere's reach
    // Within reach of the surface itself (not only of its bounding sphere: the soil beside a
    // narrow wheel, the inside of a lab frame).
    const double near_m = (radius[i] + margin_m) * (1.0 + wheelsim::kCandidateRoundOff) +
                          wheelsim::kCandidateRoundOff * s_->index->bounding_radius_m();
    if (s_->index->surface_within(R_BW * d, near_m))
      list.atoms.push_back(i);
  }
  list.neighbor_builds = neighbor->ncalls;
  list.nlocal = nlocal;
  list.clear_pending = true;
  ++(at_neighbor_build ? list.builds_at_neighbor : list.builds_between);
}

void FixWheelCosim::clear_history_outside_candidates() {
  // A particle left off the list is outside the wheel's reach until the next build: the full
  // scan would empty its history at every step with history updates; once is enough here.
  const std::vector<int> &listed = s_->candidates.atoms;
  const int *mask = atom->mask;
  std::size_t next = 0;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (next < listed.size() && listed[next] == i) {
      ++next;
      continue;
    }
    if (mask[i] & groupbit)
      wheelsim::clear_contact_slots(reinterpret_cast<wheelsim::ContactSlot *>(history_[i]),
                                    nslots_);
  }
  s_->candidates.clear_pending = false;
}

double FixWheelCosim::compute_vector(int i) { return vector_[i]; }

void FixWheelCosim::wheel_centre(double centre_m[3]) const {
  for (int k = 0; k < 3; ++k)
    centre_m[k] = s_->state.p_WB_W[k];
}

double FixWheelCosim::bounding_radius() const { return s_->index->bounding_radius_m(); }

/* ---------------------------------------------------------------------- */

void FixWheelCosim::write_vtk() {
  const std::size_t nt = s_->triangle_area_m2.size();
  std::vector<double> force(nt, 0.0), count(nt, 0.0);
  MPI_Reduce(s_->triangle_normal_force_sum.data(), force.data(), static_cast<int>(nt), MPI_DOUBLE,
             MPI_SUM, 0, world);
  MPI_Reduce(s_->triangle_contact_sum.data(), count.data(), static_cast<int>(nt), MPI_DOUBLE,
             MPI_SUM, 0, world);
  const double steps = static_cast<double>(std::max(1L, s_->vtk_window_steps));
  std::fill(s_->triangle_normal_force_sum.begin(), s_->triangle_normal_force_sum.end(), 0.0);
  std::fill(s_->triangle_contact_sum.begin(), s_->triangle_contact_sum.end(), 0.0);
  s_->vtk_window_steps = 0;
  if (comm->me != 0)
    return;
  for (std::size_t t = 0; t < nt; ++t)
    force[t] /= steps * s_->triangle_area_m2[t]; // time-averaged pressure [Pa]
  if (!s_->vtk_series)
    s_->vtk_series = std::make_unique<wheelsim::PvdSeries>(s_->vtk_prefix);
  const long step = static_cast<long>(update->ntimestep);
  const double time_s = update->get_cur_time(); // LIGGGHTS' simulation time, as in thermo 'time'
  const std::string path = s_->vtk_series->vtk_path(step);
  const char *failed = nullptr;
  if (!wheelsim::write_wheel_surface_vtk(path, s_->index->mesh(), s_->state, force, count, step,
                                         time_s))
    failed = path.c_str();
  else if (!s_->vtk_series->add(step, time_s))
    failed = s_->vtk_series->pvd_path().c_str();
  if (failed != nullptr) {
    char msg[1200];
    snprintf(msg, sizeof(msg), "fix wheel/cosim %s: cannot write '%s' (keyword vtk)", id, failed);
    error->one(FLERR, msg);
  }
}

/* ----------------------------------------------------------------------
   Per-atom storage
------------------------------------------------------------------------- */

double FixWheelCosim::memory_usage() {
  return static_cast<double>(atom->nmax) * (history_columns_ + 3) * sizeof(double);
}

void FixWheelCosim::grow_arrays(int nmax) {
  memory->grow(history_, nmax, history_columns_, "wheel/cosim:history");
  memory->grow(contact_force_, nmax, 3, "wheel/cosim:contact_force");
  array_atom = contact_force_;
}

void FixWheelCosim::copy_arrays(int i, int j, int /*delflag*/) {
  std::copy(history_[i], history_[i] + history_columns_, history_[j]);
  std::copy(contact_force_[i], contact_force_[i] + 3, contact_force_[j]);
}

void FixWheelCosim::set_arrays(int i) {
  std::fill(history_[i], history_[i] + history_columns_, 0.0);
  wheelsim::clear_contact_slots(reinterpret_cast<wheelsim::ContactSlot *>(history_[i]), nslots_);
  std::fill(contact_force_[i], contact_force_[i] + 3, 0.0);
}

int FixWheelCosim::pack_exchange(int i, double *buf) {
  std::copy(history_[i], history_[i] + history_columns_, buf);
  return history_columns_;
}

int FixWheelCosim::unpack_exchange(int nlocal, double *buf) {
  ++s_->candidates.arrived;
  std::copy(buf, buf + history_columns_, history_[nlocal]);
  std::fill(contact_force_[nlocal], contact_force_[nlocal] + 3, 0.0);
  return history_columns_;
}

int FixWheelCosim::pack_restart(int i, double *buf) {
  buf[0] = history_columns_ + 1;
  std::copy(history_[i], history_[i] + history_columns_, buf + 1);
  return history_columns_ + 1;
}

void FixWheelCosim::unpack_restart(int nlocal, int nth) {
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; ++k)
    m += static_cast<int>(extra[nlocal][m]);
  const int stored = static_cast<int>(extra[nlocal][m]) - 1;
  if (stored != history_columns_) // per atom: a rank without atoms never gets here
    bad_local_argument(
        "the restart file holds %d history values per particle, this fix expects %d: "
        "use the same 'slots' value as the run that wrote it",
        stored, history_columns_);
  std::copy(&extra[nlocal][m + 1], &extra[nlocal][m + 1] + history_columns_, history_[nlocal]);
  std::fill(contact_force_[nlocal], contact_force_[nlocal] + 3, 0.0);
}

int FixWheelCosim::size_restart(int /*i*/) { return history_columns_ + 1; }

int FixWheelCosim::maxsize_restart() { return history_columns_ + 1; }

/* ----------------------------------------------------------------------
   Checkpoints asked for by the coupled rig (docs/coupled-runs.md, "Checkpoint and resume")
------------------------------------------------------------------------- */

void FixWheelCosim::schedule_checkpoint(long step) {
  if (s_->checkpoint_dir.empty()) {
    if (!s_->checkpoint_warned && comm->me == 0) {
      char msg[256];
      snprintf(msg, sizeof(msg),
               "fix wheel/cosim %s: the rig asks for a checkpoint at step %ld, but the fix has no "
               "'checkpoint DIR' keyword: no restart file is written (the rig's half is unpaired)",
               id, step);
      error->warning(FLERR, msg);
    }
    s_->checkpoint_warned = true;
    return;
  }
  next_reneighbor = step; // atoms remapped into the box at that step, as LIGGGHTS' 'restart' does
}

/* The wheel's state of a checkpoint, beside LIGGGHTS' restart file: the decks re-declare this
   fix only after resume.in's first 'run' (which drops the restart data of fixes not yet declared,
   as LAMMPS does), so the fix keeps its own copy. Binary, host byte order:
     char[24] "wheelsim-wheel-state 1", then doubles: step, history columns, pose (13: p, q w x y z,
     v, w), wrench (7: global vector 1-7 of the step's post_force), n, then n rows of
     (atom tag, history columns) for the particles with a non-zero history. */

namespace {
constexpr char kWheelStateMagic[24] = "wheelsim-wheel-state 1";
}

void FixWheelCosim::write_wheel_state(const std::string &path) {
  std::vector<double> mine;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (std::all_of(history_[i], history_[i] + history_columns_, [](double v) { return v == 0.0; }))
      continue;
    mine.push_back(static_cast<double>(atom->tag[i]));
    mine.insert(mine.end(), history_[i], history_[i] + history_columns_);
  }
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(comm->nprocs), offsets(comm->nprocs, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  std::vector<double> all;
  if (comm->me == 0) {
    for (int r = 1; r < comm->nprocs; ++r)
      offsets[r] = offsets[r - 1] + counts[r - 1];
    all.resize(offsets.back() + counts.back());
  }
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
              0, world);
  if (comm->me != 0)
    return;
  const wheelsim::WheelPose &st = s_->state;
  const double head[22] = {static_cast<double>(update->ntimestep),
                           static_cast<double>(history_columns_),
                           st.p_WB_W.x(),
                           st.p_WB_W.y(),
                           st.p_WB_W.z(),
                           st.q_WB.w(),
                           st.q_WB.x(),
                           st.q_WB.y(),
                           st.q_WB.z(),
                           st.v_WB_W.x(),
                           st.v_WB_W.y(),
                           st.v_WB_W.z(),
                           st.w_WB_W.x(),
                           st.w_WB_W.y(),
                           st.w_WB_W.z(),
                           vector_[0],
                           vector_[1],
                           vector_[2],
                           vector_[3],
                           vector_[4],
                           vector_[5],
                           vector_[6]};
  const double n = static_cast<double>(all.size() / (history_columns_ + 1));
  const std::string writing = path + ".writing";
  FILE *fp = fopen(writing.c_str(), "wb");
  bool ok = fp != nullptr;
  if (fp) {
    ok = fwrite(kWheelStateMagic, 1, sizeof kWheelStateMagic, fp) == sizeof kWheelStateMagic &&
         fwrite(head, sizeof(double), 22, fp) == 22 && fwrite(&n, sizeof(double), 1, fp) == 1 &&
         fwrite(all.data(), sizeof(double), all.size(), fp) == all.size();
    ok = fclose(fp) == 0 && ok;
  }
  if (!ok || std::rename(writing.c_str(), path.c_str()) != 0) {
    char msg[768];
    snprintf(msg, sizeof(msg), "fix wheel/cosim %s: cannot write the checkpoint's wheel state %s",
             id, path.c_str());
    error->one(FLERR, msg);
  }
}

void FixWheelCosim::read_wheel_state(const std::string &path) {
  // Every rank reads the (small) file and keeps the rows of its own atoms. A rank may fail to
  // read it alone (a node without the file system), so the file's errors are bad_local_argument.
  if (atom->map_style == 0)
    bad_argument("keyword 'resume' needs an atom map ('atom_modify map array' before read_restart, "
                 "as inputs/soilbin/resume.in has it)");
  FILE *fp = fopen(path.c_str(), "rb");
  if (!fp)
    bad_local_argument("keyword 'resume': cannot open the wheel state file '%s'", path.c_str());
  char magic[sizeof kWheelStateMagic] = {};
  double head[22], n = 0.0;
  bool ok = fread(magic, 1, sizeof magic, fp) == sizeof magic &&
            std::memcmp(magic, kWheelStateMagic, sizeof magic) == 0 &&
            fread(head, sizeof(double), 22, fp) == 22 && fread(&n, sizeof(double), 1, fp) == 1;
  const int columns = ok ? static_cast<int>(head[1]) : 0;
  std::vector<double> rows;
  if (ok && columns == history_columns_) {
    rows.resize(static_cast<std::size_t>(n) * (columns + 1));
    ok = fread(rows.data(), sizeof(double), rows.size(), fp) == rows.size();
  }
  fclose(fp);
  if (!ok)
    bad_local_argument(
        "keyword 'resume': '%s' is not a complete wheel state file of fix wheel/cosim",
        path.c_str());
  if (columns != history_columns_)
    bad_local_argument(
        "keyword 'resume': '%s' holds %d history values per particle, this fix expects "
        "%d: use the same 'slots' value as the run that wrote it",
        path.c_str(), columns, history_columns_);
  if (static_cast<long>(head[0]) != static_cast<long>(update->ntimestep))
    bad_local_argument(
        "keyword 'resume': the wheel state '%s' is of step %ld, the restart file read "
        "is of step %ld: use the restart and the wheel state of one checkpoint",
        path.c_str(), static_cast<long>(head[0]), static_cast<long>(update->ntimestep));
  int restored = 0;
  for (std::size_t r = 0; r < static_cast<std::size_t>(n); ++r) {
    const double *row = &rows[r * (columns + 1)];
    const int i = atom->map(static_cast<tagint>(row[0]));
    if (i >= 0 && i < atom->nlocal) {
      std::copy(row + 1, row + 1 + columns, history_[i]);
      ++restored;
    }
  }
  wheelsim::WheelPose &st = s_->state;
  st.p_WB_W = Eigen::Vector3d(head[2], head[3], head[4]);
  st.q_WB = Eigen::Quaterniond(head[5], head[6], head[7], head[8]);
  st.v_WB_W = Eigen::Vector3d(head[9], head[10], head[11]);
  st.w_WB_W = Eigen::Vector3d(head[12], head[13], head[14]);
  s_->restored_wrench_step = static_cast<long>(head[0]);
  std::copy(head + 15, head + 22, s_->restored_wrench.begin());
  s_->state_step = -1;
  first_setup_ = false;
  int total = 0;
  MPI_Allreduce(&restored, &total, 1, MPI_INT, MPI_SUM, world);
  if (total != static_cast<int>(n))
    bad_argument("keyword 'resume': %d of the %ld particle histories in '%s' found no atom "
                 "(not the restart file of the same checkpoint?)",
                 static_cast<int>(n) - total, static_cast<long>(n), path.c_str());
  if (comm->me == 0) {
    char line[512];
    snprintf(line, sizeof(line),
             "fix wheel/cosim %s: resumed from %s (step %ld, centre %g %g %g m, %d particle "
             "histories)\n",
             id, path.c_str(), static_cast<long>(head[0]), head[2], head[3], head[4], total);
    wheelsim::print_line(lmp, comm->me, line);
  }
}

void FixWheelCosim::write_checkpoint() {
  // Written at the end of the step (positions, velocities and contact histories of this step,
  // the wheel pose of this step in this fix's global restart data), to a temporary name first:
  // a process killed while writing leaves no file that looks complete. Then DIR/
  // liggghts-<step>.restart.info (step, time, inputs hash, ranks), also by rename; the wheel's
  // own state (liggghts-<step>.restart.wheel) is written first.
  const long step = static_cast<long>(update->ntimestep);
  const std::string base = s_->checkpoint_dir + "/liggghts-" + std::to_string(step) + ".restart";
  write_wheel_state(base + ".wheel");
  std::string writing = base + ".writing";
  WriteRestart writer(lmp);
  writer.write(&writing[0]);
  if (comm->me == 0) {
    const std::string info = base + ".info", info_writing = info + ".writing";
    FILE *fp = fopen(info_writing.c_str(), "w");
    bool ok = fp != nullptr;
    if (fp) {
      ok = fprintf(fp,
                   "wheelsim-liggghts-checkpoint 1\nstep %ld\ntime %.17g\ninputs_hash %s\n"
                   "nprocs %d\nrestart liggghts-%ld.restart\n",
                   step, update->get_cur_time(), s_->inputs_hash.c_str(), comm->nprocs, step) > 0;
      ok = fclose(fp) == 0 && ok;
    }
    if (!ok || std::rename(writing.c_str(), base.c_str()) != 0 ||
        std::rename(info_writing.c_str(), info.c_str()) != 0) {
      char msg[1024];
      snprintf(msg, sizeof(msg),
               "fix wheel/cosim %s: cannot write the checkpoint %s (and its .info) at step %ld: "
               "check that the directory '%s' exists and is writable",
               id, base.c_str(), step, s_->checkpoint_dir.c_str());
      error->one(FLERR, msg);
    }
    // Keep the newest two: if this process dies while writing the next one, the rig's and this
    // side's previous checkpoint still pair up.
    s_->checkpoint_steps.push_back(step);
    while (s_->checkpoint_steps.size() > 2) {
      const std::string old = s_->checkpoint_dir + "/liggghts-" +
                              std::to_string(s_->checkpoint_steps.front()) + ".restart";
      std::remove((old + ".info").c_str());
      std::remove((old + ".wheel").c_str());
      std::remove(old.c_str());
      s_->checkpoint_steps.erase(s_->checkpoint_steps.begin());
    }
    char line[512];
    snprintf(line, sizeof(line), "fix wheel/cosim %s: checkpoint %s written at step %ld\n", id,
             base.c_str(), step);
    wheelsim::print_line(lmp, comm->me, line);
  }
}

/* ----------------------------------------------------------------------
   Global restart state: the wheel pose and twist
------------------------------------------------------------------------- */

void FixWheelCosim::write_restart(FILE *fp) {
  // Format 2: format 1 (the pose and twist) + the step and the wrench (global vector 1-7) this
  // fix computed in that step's post_force, which a coupled run resumed from this file sends to
  // the rig again (setup() would recompute it from the end-of-step velocities).
  const wheelsim::WheelPose &st = s_->state;
  double list[22] = {2.0, // format version
                     st.p_WB_W.x(), st.p_WB_W.y(),
                     st.p_WB_W.z(), st.q_WB.w(),
                     st.q_WB.x(),   st.q_WB.y(),
                     st.q_WB.z(),   st.v_WB_W.x(),
                     st.v_WB_W.y(), st.v_WB_W.z(),
                     st.w_WB_W.x(), st.w_WB_W.y(),
                     st.w_WB_W.z(), static_cast<double>(update->ntimestep)};
  std::copy(vector_, vector_ + 7, list + 15);
  if (comm->me == 0) {
    const int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 22, fp);
  }
}

void FixWheelCosim::restart(char *buf) {
  const double *list = reinterpret_cast<const double *>(buf);
  if (list[0] != 1.0 && list[0] != 2.0)
    bad_argument("restart data of fix wheel/cosim has format %g, expected 1 or 2", list[0]);
  if (list[0] == 2.0) {
    s_->restored_wrench_step = static_cast<long>(list[14]);
    std::copy(list + 15, list + 22, s_->restored_wrench.begin());
  }
  wheelsim::WheelPose &st = s_->state;
  st.p_WB_W = Eigen::Vector3d(list[1], list[2], list[3]);
  st.q_WB = Eigen::Quaterniond(list[4], list[5], list[6], list[7]).normalized();
  st.v_WB_W = Eigen::Vector3d(list[8], list[9], list[10]);
  st.w_WB_W = Eigen::Vector3d(list[11], list[12], list[13]);
  s_->state_step = -1;  // setup() marks the pose as that of the restart step
  first_setup_ = false; // particles touching a wheel restored mid-run are not an error
  if (comm->me == 0) {
    char line[256];
    snprintf(line, sizeof(line),
             "fix wheel/cosim %s: pose restored from the restart file (centre %g %g %g m); "
             "keyword 'origin' ignored\n",
             id, list[1], list[2], list[3]);
    wheelsim::print_line(lmp, comm->me, line);
  }
}
