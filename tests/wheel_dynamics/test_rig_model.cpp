// The rig model against closed forms: free fall, the suspension's natural frequency, energy
// conservation of the symplectic Euler integrator without damping, its stability limit (the
// time-step bound of time_step.h).
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "wheelsim/rig/flat_ground.h"
#include "wheelsim/rig/rig_model.h"
#include "wheelsim/rig/time_step.h"

namespace wheelsim::rig {
namespace {

RigParameters reference_rig() {
  RigParameters p; // TERRAMECHANICS.md §8
  p.wheel_mass_kg = 205.0;
  p.wheel_axle_inertia_kg_m2 = 72.0;
  p.spindle_mass_kg = 100.0;
  p.suspended_mass_kg = 1000.0;
  p.spring_k_N_m = 12000.0;
  p.spring_c_N_s_m = 800.0;
  return p;
}

// Free fall without terrain: the centre of mass of the vertical DOFs falls as z0 + v0 t - g t^2/2
// (the spring is internal). Symplectic Euler's exact discrete solution is that minus g dt t / 2
// (first-order error); the carriage and the wheel keep their speeds exactly.
TEST(RigModel, FreeFallMatchesAnalytic) {
  const RigParameters p = reference_rig();
  RigCoordinates q0;
  q0.z_m = 2.0;
  q0.mass_z_m = 2.0 - 0.05; // spring compressed: the internal oscillation must not matter
  RigVelocities u0;
  u0.x_m_s = 0.5;
  u0.z_m_s = 0.3;
  u0.mass_z_m_s = 0.3;
  u0.omega_rad_s = 2.0;
  Rig rig(p, q0, u0);
  const double dt = 1e-4, g = p.gravity_m_s2;
  const double Mz = rig.spindle_dof_mass_kg(), Mm = p.suspended_mass_kg;
  const double zc0 = (Mz * q0.z_m + Mm * q0.mass_z_m) / (Mz + Mm);
  const int n = 10000;
  for (int i = 0; i < n; ++i)
    rig.step(WheelWrench{}, dt);
  const double t = n * dt;
  const auto &q = rig.coordinates();
  const double zc = (Mz * q.z_m + Mm * q.mass_z_m) / (Mz + Mm);
  const double analytic = zc0 + 0.3 * t - 0.5 * g * t * t;
  EXPECT_NEAR(zc, analytic - 0.5 * g * dt * t, 1e-9);   // the integrator's exact discrete value
  EXPECT_NEAR(zc, analytic, 0.5 * g * dt * t * 1.0001); // O(dt) away from the closed form
  EXPECT_NEAR(rig.velocities().z_m_s * Mz + rig.velocities().mass_z_m_s * Mm,
              (Mz + Mm) * (0.3 - g * t), 1e-8);
  EXPECT_NEAR(q.x_m, 0.5 * t, 1e-12);
  EXPECT_NEAR(q.theta_rad, 2.0 * t, 1e-12);
  EXPECT_DOUBLE_EQ(rig.velocities().omega_rad_s, 2.0);
  const WheelPose s = rig.wheel_state();
  EXPECT_NEAR(s.q_WB.norm(), 1.0, 1e-15);
  // Positive θ about +y: the wheel's forward point (+x) turns downwards (-z).
  const Eigen::Vector3d fwd = s.q_WB * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(fwd.x(), std::cos(2.0 * t), 1e-12);
  EXPECT_NEAR(fwd.z(), -std::sin(2.0 * t), 1e-12);
}

// Spindle held, no damping: the suspended mass oscillates at sqrt(k/m). Period from upward zero
// crossings (linear interpolation) over ~20 periods. Symplectic Euler's frequency error is
// (ω dt)^2/24 ~ 5e-9 here, far below the 0.1 % asked for.
void check_natural_frequency(double k, double m) {
  RigParameters p = reference_rig();
  p.spring_k_N_m = k;
  p.suspended_mass_kg = m;
  p.spring_c_N_s_m = 0.0;
  const double omega = std::sqrt(k / m), g = p.gravity_m_s2;
  RigCoordinates q0;
  q0.z_m = 1.0;
  const double eq = q0.z_m - m * g / k; // static equilibrium of the mass
  q0.mass_z_m = eq + 0.01;
  Rig rig(p, q0, RigVelocities{});
  RigDrives d;
  d.spindle = Drive::imposed_velocity;
  d.spindle_velocity_m_s = 0.0;
  rig.set_drives(d);
  const double dt = 1e-4;
  const double T = 2 * M_PI / omega;
  std::vector<double> crossings;
  double prev = rig.coordinates().mass_z_m - eq;
  while (rig.time_s() < 20.5 * T) {
    const double t0 = rig.time_s();
    rig.step(WheelWrench{}, dt);
    const double cur = rig.coordinates().mass_z_m - eq;
    if (prev < 0 && cur >= 0)
      crossings.push_back(t0 + dt * (-prev) / (cur - prev));
    prev = cur;
    ASSERT_DOUBLE_EQ(rig.coordinates().z_m, 1.0); // held
  }
  ASSERT_GE(crossings.size(), 19u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double measured = 2 * M_PI / period;
  EXPECT_NEAR(measured / omega, 1.0, 1e-3) << "k " << k << " m " << m;
  EXPECT_NEAR(measured / omega, 1.0, 1e-5) << "(much better than asked: check the integrator)";
  // The holder carries the whole weight on average: spring + spindle weight.
  EXPECT_GT(rig.reactions().spindle_support_force_N, 0.0);
}

TEST(RigModel, SuspensionNaturalFrequencyWithin0p1Percent) {
  check_natural_frequency(12000.0, 1000.0);
  check_natural_frequency(12000.0, 300.0);
  check_natural_frequency(50000.0, 2000.0);
}

// Energy without damping: the spindle rests on a frictionless, undamped penalty ground, the
// suspended mass on an undamped spring; the carriage and the wheel move at constant speed. The
// vertical system is linear (contact stays closed), so each mode i is a harmonic oscillator of
// frequency ω_i, for which symplectic Euler conserves the modified energy
// H~ = H - (dt/2) ω_i^2 x v exactly; since ω |x v| <= H, the energy stays within
// |E_n - E_0| <= ω_max dt E_osc / (1 - (ω_max dt / 2)^2) of its start (E_osc: the oscillation
// energy above the equilibrium): first order in dt, bounded, no drift over any number of steps.
struct EnergyRun {
  double max_error_J = 0.0;
  double bound_J = 0.0;
  double mean_first_J = 0.0, mean_last_J = 0.0;
};

EnergyRun run_energy(double dt, int steps) {
  RigParameters p = reference_rig();
  p.spring_c_N_s_m = 0.0;
  FlatGroundParameters gp;
  gp.radius_m = 0.6;
  gp.stiffness_N_m = 1e7;
  gp.damping_N_s_m = 0.0;
  gp.friction = 0.0;
  FlatGround ground(gp);
  const double g = p.gravity_m_s2;
  const double W = (p.wheel_mass_kg + p.spindle_mass_kg + p.suspended_mass_kg) * g;
  const double z_eq = gp.radius_m - W / gp.stiffness_N_m;
  const double zm_eq = z_eq - p.suspended_mass_kg * g / p.spring_k_N_m;
  auto total = [&](const Rig &rig) {
    const double pen = gp.radius_m - rig.coordinates().z_m;
    return rig.energy().total_J() + (pen > 0 ? 0.5 * gp.stiffness_N_m * pen * pen : 0.0);
  };
  RigVelocities u0;
  u0.x_m_s = 0.4;
  u0.omega_rad_s = 0.7;
  const Rig at_eq(p, RigCoordinates{0, z_eq, zm_eq, 0}, u0);
  Rig rig(p, RigCoordinates{0, z_eq + 3e-4, zm_eq + 0.01, 0}, u0);
  const double E0 = total(rig);
  const double E_osc = E0 - total(at_eq);

  // Highest mode of the two vertical DOFs (spindle on the ground spring, suspended mass on the
  // suspension spring): the larger root of det(K - w^2 M) = 0 with diagonal M,
  // m1 m2 w^4 - (K11 m2 + K22 m1) w^2 + (K11 K22 - K12^2) = 0.
  const double k11 = gp.stiffness_N_m + p.spring_k_N_m, k22 = p.spring_k_N_m, k12 = -p.spring_k_N_m;
  const double m1 = rig.spindle_dof_mass_kg(), m2 = p.suspended_mass_kg;
  const double half_b = 0.5 * (k11 * m2 + k22 * m1) / (m1 * m2);
  const double c = (k11 * k22 - k12 * k12) / (m1 * m2);
  const double w_max = std::sqrt(half_b + std::sqrt(half_b * half_b - c));
  const double a = w_max * dt / 2;

  EnergyRun r;
  r.bound_J = w_max * dt * E_osc / (1 - a * a);
  const int window = steps / 10;
  for (int i = 0; i < steps; ++i) {
    rig.step(ground.contact(rig.wheel_state(), rig.time_s()), dt);
    const double err = total(rig) - E0;
    r.max_error_J = std::max(r.max_error_J, std::abs(err));
    if (i < window)
      r.mean_first_J += err / window;
    if (i >= steps - window)
      r.mean_last_J += err / window;
    EXPECT_LT(rig.coordinates().z_m, gp.radius_m) << "contact opened: the bound assumes it closed";
  }
  EXPECT_NEAR(rig.velocities().x_m_s, 0.4, 1e-15);
  EXPECT_NEAR(rig.velocities().omega_rad_s, 0.7, 1e-15);
  return r;
}

TEST(RigModel, EnergyConservedWithoutDampingOver1e5Steps) {
  const EnergyRun r = run_energy(1e-4, 100000);
  RecordProperty("max_energy_error_J", std::to_string(r.max_error_J));
  RecordProperty("bound_J", std::to_string(r.bound_J));
  EXPECT_LE(r.max_error_J, r.bound_J);
  EXPECT_GT(r.max_error_J, 0.05 * r.bound_J) << "suspiciously exact: is the contact active?";
  // No drift: the mean error of the last 10 % of the run equals that of the first 10 %.
  EXPECT_NEAR(r.mean_last_J, r.mean_first_J, 0.05 * r.bound_J);
  // First order: halving dt halves the (bounded) error.
  const EnergyRun h = run_energy(0.5e-4, 100000);
  EXPECT_LE(h.max_error_J, h.bound_J);
  const double ratio = r.max_error_J / h.max_error_J;
  EXPECT_GT(ratio, 1.6);
  EXPECT_LT(ratio, 2.4);
}

TEST(RigModel, DampingDissipatesEnergy) {
  RigParameters p = reference_rig();
  RigCoordinates q0;
  q0.z_m = 1.0;
  q0.mass_z_m = 1.0 - p.suspended_mass_kg * p.gravity_m_s2 / p.spring_k_N_m + 0.01;
  Rig rig(p, q0, RigVelocities{});
  RigDrives d;
  d.spindle = Drive::imposed_velocity;
  rig.set_drives(d);
  const double E0 = rig.energy().total_J();
  for (int i = 0; i < 50000; ++i)
    rig.step(WheelWrench{}, 1e-4);
  // ζ = c / (2 sqrt(k m)) = 0.115: after 5 s (2.8 periods) the amplitude is e^{-ζ ω t} = 0.14.
  const double E_osc0 = 0.5 * p.spring_k_N_m * 0.01 * 0.01;
  const double lost = E0 - rig.energy().total_J();
  EXPECT_GT(lost, 0.9 * E_osc0);
  EXPECT_LT(lost, E_osc0);
}

TEST(RigModel, ImposedVelocitiesAndReactions) {
  const RigParameters p = reference_rig();
  Rig rig(p, RigCoordinates{0, 1.0, 0.5, 0}, RigVelocities{});
  RigDrives d;
  d.wheel = Drive::imposed_velocity;
  d.wheel_value = 1.0;
  d.carriage = Drive::follow_wheel;
  d.carriage_value = 0.8 * 0.6; // slip 0.2 at R 0.6
  d.spindle = Drive::imposed_velocity;
  rig.set_drives(d);
  WheelWrench w;
  w.f_B_W = Eigen::Vector3d(100.0, 7.0, 0.0);
  w.t_B_W = Eigen::Vector3d(3.0, -60.0, 5.0);
  rig.step(w, 1e-3);
  EXPECT_DOUBLE_EQ(rig.velocities().omega_rad_s, 1.0);
  EXPECT_DOUBLE_EQ(rig.velocities().x_m_s, 0.48);
  // Motor: I dω/dt = T_motor + T_contact.
  EXPECT_NEAR(rig.reactions().motor_torque_Nm, 72.0 * 1.0 / 1e-3 + 60.0, 1e-9);
  EXPECT_NEAR(rig.reactions().carriage_force_N, rig.longitudinal_mass_kg() * 0.48 / 1e-3 - 100.0,
              1e-7);
  EXPECT_DOUBLE_EQ(rig.reactions().held_force_y_N, 7.0);
  EXPECT_DOUBLE_EQ(rig.reactions().held_torque_x_Nm, 3.0);
  EXPECT_DOUBLE_EQ(rig.reactions().held_torque_z_Nm, 5.0);
  EXPECT_THROW(rig.step(w, 0.0), std::invalid_argument);
  RigParameters bad = p;
  bad.spring_k_N_m = -3;
  EXPECT_THROW(Rig(bad, RigCoordinates{}, RigVelocities{}), std::invalid_argument);
}

TEST(RigModel, TimeIsStepCountTimesDtNotASumOfSteps) {
  // Summing dt drifts: 4000 steps of 5e-4 s summed give 1.9999999999998... and a snapshot at
  // 2.0 s fired one step late. Time is t0 + n dt, exactly as the step count says.
  Rig rig(reference_rig(), RigCoordinates{}, RigVelocities{}, 0.25);
  for (int i = 0; i < 4000; ++i)
    rig.step(WheelWrench{}, 5e-4);
  EXPECT_EQ(rig.time_s(), 0.25 + 4000 * 5e-4);
  for (int i = 0; i < 3; ++i) // a new time step continues from where the old one ended
    rig.step(WheelWrench{}, 1e-3);
  EXPECT_EQ(rig.time_s(), (0.25 + 4000 * 5e-4) + 3 * 1e-3);
}

// The time-step bound is the integrator's own stability limit: the suspended mass on its spring
// and damper (the spindle held, as in the release phase) stays bounded at 0.98 of
// OscillatorMode::stable_time_step_s() and grows at 1.02 of it; damped, undamped, and the light
// suspended mass of the small test rig (inputs/rigs/small_wheel_scm.toml, 0.029 kg on 30 N s/m:
// damping-limited).
TEST(TimeStep, BoundIsTheIntegratorsStabilityLimit) {
  struct Case {
    double k_N_m, c_N_s_m, mass_kg;
  };
  for (const Case c : {Case{12000.0, 800.0, 1040.0}, Case{12000.0, 0.0, 1040.0},
                       Case{3000.0, 30.0, 0.0291}, Case{0.0, 30.0, 0.0291}}) {
    SCOPED_TRACE(testing::Message() << "k " << c.k_N_m << " c " << c.c_N_s_m << " m " << c.mass_kg);
    RigParameters p = reference_rig();
    p.spring_k_N_m = std::max(c.k_N_m, 1e-12); // the Rig needs k > 0; 1e-12 N/m is none here
    p.spring_c_N_s_m = c.c_N_s_m;
    p.suspended_mass_kg = c.mass_kg;
    const OscillatorMode mode{"", c.k_N_m, c.c_N_s_m, c.mass_kg};
    const double limit_s = mode.stable_time_step_s();
    if (c.c_N_s_m == 0.0) {
      EXPECT_NEAR(limit_s, 2.0 / std::sqrt(c.k_N_m / c.mass_kg), 1e-12 * limit_s); // 2/omega
    }
    if (c.k_N_m == 0.0) {
      EXPECT_NEAR(limit_s, 2.0 * c.mass_kg / c.c_N_s_m, 1e-12 * limit_s); // 2 m/c
    }
    // The deviation from the rest state: the extension from its static value (spring), or the
    // speed from the terminal speed -m g/c (the damper alone).
    const double rest_extension_m = -c.mass_kg * p.gravity_m_s2 / p.spring_k_N_m;
    const double terminal_speed_m_s = -c.mass_kg * p.gravity_m_s2 / std::max(c.c_N_s_m, 1e-300);
    const bool spring = c.k_N_m > 0.0;
    for (const double factor : {0.98, 1.02}) {
      RigCoordinates q0;
      RigVelocities u0;
      if (spring)
        q0.mass_z_m = q0.z_m + rest_extension_m + 0.01; // 1 cm off its rest
      else
        u0.mass_z_m_s = terminal_speed_m_s + 1.0; // 1 m/s off its terminal speed
      const auto deviation = [&](const Rig &rig) {
        return spring ? std::abs(rig.spring_extension_m() - rest_extension_m) / 0.01
                      : std::abs(rig.velocities().mass_z_m_s - terminal_speed_m_s) / 1.0;
      };
      Rig rig(p, q0, u0);
      RigDrives held; // spindle, wheel and carriage held still
      held.spindle = Drive::imposed_velocity;
      held.wheel = Drive::imposed_velocity;
      held.carriage = Drive::imposed_velocity;
      rig.set_drives(held);
      double largest = 0.0;
      for (int i = 0; i < 2000 && largest < 1e6; ++i) {
        rig.step(WheelWrench{}, factor * limit_s);
        largest = std::max(largest, deviation(rig));
      }
      if (factor < 1.0)
        EXPECT_LT(largest, 10.0) << "unstable below the bound";
      else
        EXPECT_GT(largest, 1e3) << "stable above the bound: the bound is not the limit";
    }
  }
}

} // namespace
} // namespace wheelsim::rig
