#include "scm_rig_run.h"

#include <cmath>
#include <sstream>
#include <vector>

namespace wheelsim::test {

std::string scm_rig_config_text(const ScmRunSpec &s) {
  std::ostringstream t;
  t.precision(17);
  t << "[wheel]\nmesh = \"" << WHEELSIM_MESH_DIR << "/" << s.wheel << ".obj\"\n"
    << "mass = 205.0\ninertia = 72.0\n"
    << "[rig]\nspindle_mass = 100.0\nvertical_load = " << s.load_N
    << "\nspring_k = 12000.0\nspring_c = 800.0\n"
    << "[motor]\nomega = 1.05\nramp_time = 0.5\n"
    << "[carriage]\nmode = \"imposed_slip\"\nslip = " << s.slip << "\n"
    << "[run]\ndt = " << s.dt_s << "\nduration = " << s.test_duration_s
    << "\nrelease_gap = 0.002\nrelease_speed = 0.02\nrelease_timeout = 20.0\n"
    << "settle_velocity = 0.001\nsettle_window = 0.1\nsettle_min_time = 0.3\n"
    << "settle_max_time = 3.0\n"
    << "[terrain]\ntype = \"scm\"\nsoil = \"" << WHEELSIM_SOIL_DIR << "/" << s.soil << ".toml\"\n"
    << "grid_spacing = " << s.grid_spacing_m << "\n"
    << "normal_direction = \"" << (s.vertical_normal ? "vertical" : "surface") << "\"\n"
    << "shear_surface = \"" << (s.shear_at_lug_tips ? "lug_tips" : "wheel") << "\"\n"
    << "bulldozing = " << (s.bulldozing ? "true" : "false") << "\n";
  if (s.bulldozing)
    t << "flow_factor = " << s.flow_factor << "\n";
  if (s.elastic_K_Pa_m > 0)
    t << "elastic_stiffness = " << s.elastic_K_Pa_m << "\n";
  t << "[output]\nprogress_interval = 0\n";
  return t.str();
}

namespace {

struct Stats {
  std::vector<double> v;
  double mean() const {
    double sum = 0;
    for (double x : v)
      sum += x;
    return v.empty() ? NAN : sum / v.size();
  }
  double std() const {
    const double m = mean();
    double sum = 0;
    for (double x : v)
      sum += (x - m) * (x - m);
    return v.empty() ? NAN : std::sqrt(sum / v.size());
  }
};

} // namespace

ScmRunResult run_scm_rig(const ScmRunSpec &spec, std::shared_ptr<rig::ScmGround> *ground_inout) {
  const rig::RigConfig config = rig::parse_rig_config(scm_rig_config_text(spec), "scm_rig_test");
  rig::RigSimulation sim(config);
  std::shared_ptr<rig::ScmGround> ground;
  if (ground_inout && *ground_inout)
    ground = *ground_inout;
  else
    ground = std::make_shared<rig::ScmGround>(config, sim.wheel());
  if (ground_inout)
    *ground_inout = ground;

  const double window_start_s = 0.5 * spec.test_duration_s;
  Stats sinkage, dp, torque, slip;
  double x_first = NAN, x_last = NAN;
  ScmRunResult r;
  sim.run(*ground, [&](const rig::RigOutputs &o) {
    ++r.steps;
    if (o.phase != rig::Phase::test || o.time_s - sim.test_start_s() < window_start_s)
      return;
    sinkage.v.push_back(o.sinkage_m);
    dp.v.push_back(o.drawbar_pull_N);
    torque.v.push_back(o.driving_torque_Nm);
    slip.v.push_back(o.slip);
    if (std::isnan(x_first))
      x_first = o.wheel.p_WB_W.x();
    x_last = o.wheel.p_WB_W.x();
  });
  r.sinkage_m = sinkage.mean();
  r.sinkage_std_m = sinkage.std();
  r.drawbar_pull_N = dp.mean();
  r.drawbar_pull_std_N = dp.std();
  r.driving_torque_Nm = torque.mean();
  r.slip = slip.mean();
  r.static_sinkage_m = sim.static_sinkage_m();
  // The rut left on the centre line over the window's first half (the wheel has passed it),
  // below the undisturbed surface.
  const double rim = sim.wheel().rim_radius_m;
  const scm::FieldMap rut = ground->terrain().sample(scm::Field::height, x_first - rim,
                                                     0.5 * (x_first + x_last) - rim, -0.01, 0.01);
  Stats depth;
  for (double h : rut.values)
    depth.v.push_back(config.terrain.surface_height_m - h);
  r.rut_depth_m = depth.mean();
  return r;
}

} // namespace wheelsim::test
