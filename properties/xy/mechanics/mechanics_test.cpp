// models/xy/mechanics: the thesis equations, the torque model and the step-sequence kinematics.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <vector>

#include "models/xy/mechanics/mechanics.hpp"

namespace mech = ap::model::xy_mechanics;

namespace {

double uniform(int lo_milli, int hi_milli) {
  return static_cast<double>(*rc::gen::inRange(lo_milli, hi_milli)) / 1000.0;
}

// Step times a firmware-like ramp produces: the speed is updated once per tick (dt) by +-a*dt
// between v_start and v_max, and each step is taken after 1/step_rate of the current speed.
std::vector<mech::Step> ticked_ramp(const mech::Model& m, double distance, double v_start, double v_max, double a,
                                    double dt) {
  std::vector<mech::Step> out;
  const double dx = m.step_length();
  const auto n = static_cast<std::size_t>(std::llround(distance / dx));
  double t = 0.0;
  double v = v_start;
  double next_tick = dt;
  for (std::size_t i = 0; i < n; ++i) {
    const double remaining = static_cast<double>(n - i) * dx;
    t += dx / v;
    while (t >= next_tick) {
      const bool decel = v * v - v_start * v_start >= 2.0 * a * remaining;
      v = decel ? std::max(v_start, v - a * dt) : std::min(v_max, v + a * dt);
      next_tick += dt;
    }
    out.push_back(mech::Step{t, 1});
  }
  return out;
}

}  // namespace

TEST(mechanics_equations, RequiredTorqueWorkedExample) {
  // seed 000 §2.2: s = 2 mm, m = 5 kg, a = 5 mm/s^2, f1 = 0.1, I = 82 g cm^2.
  const double m = mech::required_torque(0.005, 0.002, 5.0, 0.1, 8.2e-6);
  EXPECT_NEAR(m, 1.69807e-3, 1e-8);
  EXPECT_NEAR(mech::accel_from_torque(m, 0.002, 5.0, 0.1, 8.2e-6), 0.005, 1e-12);
}

TEST(mechanics_equations, AngularRelations) {
  EXPECT_NEAR(mech::omega_from_speed(0.010, 0.002), 10.0 * mech::kPi, 1e-12);   // 5 rev/s
  EXPECT_NEAR(mech::epsilon_from_accel(0.002, 0.002), 2.0 * mech::kPi, 1e-12);
}

RC_GTEST_PROP(mechanics_equations, Eq45InvertsEq46, ()) {
  const double s = uniform(500, 10000) / 1000.0;     // 0.5 .. 10 mm
  const double m = uniform(100, 30000);              // 0.1 .. 30 kg
  const double f1 = uniform(0, 300);
  const double inertia = uniform(1, 100) * 1e-6;
  const double a = uniform(-2000, 2000);             // m/s^2
  const double torque = mech::required_torque(a, s, m, f1, inertia);
  RC_ASSERT(std::abs(mech::accel_from_torque(torque, s, m, f1, inertia) - a) <= 1e-9 * (1.0 + std::abs(a)));
}

RC_GTEST_PROP(mechanics_equations, ReducedMassConservesKineticEnergy, ()) {
  const double s = uniform(500, 10000) / 1000.0;
  const double m = uniform(100, 30000);
  const double inertia = uniform(1, 100) * 1e-6;
  const double v = uniform(0, 200) / 1000.0;
  const double w = mech::omega_from_speed(v, s);
  const double lhs = 0.5 * mech::reduced_mass(m, inertia, s) * v * v;
  const double rhs = 0.5 * m * v * v + 0.5 * inertia * w * w;
  RC_ASSERT(std::abs(lhs - rhs) <= 1e-9 * (1.0 + rhs));
}

TEST(mechanics_motor, TorqueCurveIsFlatThenFalls) {
  const mech::Model model;
  const double vc = model.corner_speed();
  ASSERT_GT(vc, 0.0);
  const double t0 = model.torque_available(0.0);
  EXPECT_NEAR(t0, 0.7 * 0.560, 1e-12);
  EXPECT_NEAR(model.torque_available(0.5 * vc), t0, 1e-12);
  EXPECT_NEAR(model.torque_available(vc), t0, 1e-9);
  EXPECT_LT(model.torque_available(2.0 * vc), 0.6 * t0);
  double prev = t0;
  for (double v = 0.0; v < 0.2; v += 0.001) {
    const double now = model.torque_available(v);
    EXPECT_LE(now, prev + 1e-15);
    EXPECT_DOUBLE_EQ(model.torque_available(-v), now);
    prev = now;
  }
}

TEST(mechanics_motor, StepGeometry) {
  const mech::Model model;   // 2 mm lead, 200 full steps, 16 microsteps
  EXPECT_DOUBLE_EQ(model.steps_per_rev(), 3200.0);
  EXPECT_NEAR(model.step_length(), 0.625e-6, 1e-15);
}

TEST(mechanics_simulate, ConstantSpeedHasNoAcceleration) {
  const mech::Model model;
  std::vector<mech::Step> steps;
  const double v = 0.005;
  for (int i = 1; i <= 4000; ++i) {
    steps.push_back({i * model.step_length() / v, 1});
  }
  const auto r = mech::simulate(model, steps);
  ASSERT_EQ(r.summary.segments, 1U);
  ASSERT_EQ(r.samples.size(), steps.size() + 2);   // + start and stop
  for (std::size_t i = 1; i + 1 < r.samples.size(); ++i) {
    EXPECT_NEAR(r.samples[i].v, v, 1e-9);
    EXPECT_NEAR(r.samples[i].a, 0.0, 1e-6);
    EXPECT_EQ(r.samples[i].risk, mech::Risk::none);
  }
  EXPECT_NEAR(r.samples.back().x, 4000 * model.step_length(), 1e-12);
  EXPECT_EQ(r.summary.lost_step_risks, 0U);
}

TEST(mechanics_simulate, Thesis20mmMoveAt10mmPerSecond) {
  // §9.1.1: 20 mm absolute move, saturating at 10 mm/s; a = 20 mm/s^2 gives t = 2.5 s.
  const mech::Model model;
  const auto steps = mech::trapezoid_steps(model, 0.020, 0.0, 0.010, 0.020);
  ASSERT_EQ(steps.size(), 32000U);
  EXPECT_NEAR(steps.back().t, 2.5, 1e-9);
  const auto r = mech::simulate(model, steps);
  EXPECT_NEAR(r.samples.back().x, 0.020, 1e-12);
  EXPECT_NEAR(r.summary.max_speed, 0.010, 0.0001);
  EXPECT_LT(r.summary.max_accel, 0.020 * 1.10);
  EXPECT_EQ(r.summary.lost_step_risks, 0U);
  EXPECT_EQ(r.summary.warnings, 0U);
  EXPECT_GT(r.summary.min_margin, 10.0);
}

TEST(mechanics_simulate, TickQuantisedRampKeepsItsAcceleration) {
  const mech::Model model;
  const auto steps = ticked_ramp(model, 0.020, 0.0005, 0.010, 0.005, 0.001);
  const auto r = mech::simulate(model, steps);
  double max_a = 0.0;
  for (std::size_t i = 1; i + 1 < r.samples.size(); ++i) {
    max_a = std::max(max_a, std::abs(r.samples[i].a));
  }
  EXPECT_LT(max_a, 0.005 * 1.5);   // the window filters the per-tick speed jumps
  EXPECT_GT(max_a, 0.005 * 0.7);
  EXPECT_NEAR(r.summary.max_speed, 0.010, 0.0002);
}

RC_GTEST_PROP(mechanics_simulate, TrapezoidKinematicsMatchTheProfile, ()) {
  const mech::Model model;
  const double d = uniform(100, 5000) / 1000.0 / 1000.0 * 4.0;  // 0.4 .. 20 mm
  const double vmax = uniform(1000, 20000) / 1000.0 / 1000.0;   // 1 .. 20 mm/s
  const double a = uniform(1000, 100000) / 1000.0 / 1000.0;     // 1 .. 100 mm/s^2
  const int sign = *rc::gen::element(-1, 1);
  const auto steps = mech::trapezoid_steps(model, sign * d, 0.0, vmax, a);
  const auto r = mech::simulate(model, steps);
  RC_ASSERT(std::abs(r.samples.back().x - sign * d) < model.step_length());
  for (std::size_t i = 1; i + 1 < r.samples.size(); ++i) {
    RC_ASSERT(std::abs(r.samples[i].v) <= vmax * 1.02 + 1e-6);
    RC_ASSERT(r.samples[i].v * sign >= -1e-9);
  }
  RC_ASSERT(r.summary.lost_step_risks == 0U);
}

TEST(mechanics_simulate, ViolentAccelerationIsALostStepRisk) {
  const mech::Model model;
  // 40 m/s^2 asks ~1 N*m from a 0.56 N*m motor (the screw and rotor inertia dominate).
  const auto steps = mech::trapezoid_steps(model, 0.010, 0.0, 0.2, 40.0);
  const auto r = mech::simulate(model, steps);
  EXPECT_GT(r.summary.lost_step_risks, 0U);
  ASSERT_TRUE(r.summary.first_risk_t.has_value());
  EXPECT_LT(*r.summary.first_risk_t, 0.01);
  EXPECT_LT(r.summary.min_margin, 1.0);
}

TEST(mechanics_simulate, TooFastStartWithoutRampIsFlagged) {
  // Starting at 100 mm/s from rest (no ramp) needs the rotor at speed within one full step.
  const mech::Model model;
  std::vector<mech::Step> steps;
  for (int i = 1; i <= 200; ++i) {
    steps.push_back({i * model.step_length() / 0.1, 1});
  }
  const auto r = mech::simulate(model, steps);
  EXPECT_EQ(r.samples.front().risk, mech::Risk::lost_step);
  EXPECT_EQ(r.samples.back().risk, mech::Risk::lost_step);
}

TEST(mechanics_simulate, SegmentsSplitAtRestAndReversal) {
  const mech::Model model;
  std::vector<mech::Step> steps;
  double t = 0.0;
  for (int i = 0; i < 50; ++i) steps.push_back({t += 0.001, 1});
  t += 0.2;   // rest
  for (int i = 0; i < 50; ++i) steps.push_back({t += 0.001, 1});
  for (int i = 0; i < 50; ++i) steps.push_back({t += 0.001, -1});   // reversal
  const auto r = mech::simulate(model, steps);
  EXPECT_EQ(r.summary.segments, 3U);
  EXPECT_NEAR(r.samples.back().x, 50 * model.step_length(), 1e-12);
}

TEST(mechanics_simulate, RejectsBadInput) {
  const mech::Model model;
  const std::vector<mech::Step> backwards{{0.2, 1}, {0.1, 1}};
  EXPECT_THROW(mech::simulate(model, backwards), std::invalid_argument);
  const std::vector<mech::Step> bad_dir{{0.1, 0}};
  EXPECT_THROW(mech::simulate(model, bad_dir), std::invalid_argument);
  mech::Params p;
  p.axis.lead = 0.0;
  EXPECT_THROW(mech::Model{p}, std::invalid_argument);
  EXPECT_TRUE(mech::simulate(model, std::vector<mech::Step>{}).samples.empty());
}

// The incremental tracker gives exactly the batch result, whatever the flush times.
RC_GTEST_PROP(mechanics_tracker, MatchesBatchSimulation, ()) {
  const mech::Model model;
  std::vector<mech::Step> steps;
  double t0 = 0.0;
  const auto moves = *rc::gen::inRange(1, 4);
  for (int m = 0; m < moves; ++m) {
    const double d = uniform(50, 300) / 1e3 * (*rc::gen::element(-1.0, 1.0));   // 0.05 .. 0.3 mm
    const auto part = mech::trapezoid_steps(model, d, 0.0005, 0.005, 0.05, t0);
    steps.insert(steps.end(), part.begin(), part.end());
    t0 = steps.back().t + uniform(0, 300) / 1000.0;   // sometimes no rest: segments split on DIR only
  }
  const auto batch = mech::simulate(model, steps);
  mech::Tracker tr(model);
  std::vector<mech::Sample> got;
  double next_flush = uniform(1, 100) / 1000.0;
  for (const auto& s : steps) {
    while (s.t > next_flush) {
      auto part = tr.flush(next_flush);
      got.insert(got.end(), part.begin(), part.end());
      next_flush += uniform(1, 200) / 1000.0;
    }
    tr.step(s.t, s.dir);
  }
  auto rest = tr.finish();
  got.insert(got.end(), rest.begin(), rest.end());
  RC_ASSERT(got.size() == batch.samples.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    RC_ASSERT(std::abs(got[i].x - batch.samples[i].x) < 1e-12);
    RC_ASSERT(got[i].t == batch.samples[i].t);
    RC_ASSERT(std::abs(got[i].a - batch.samples[i].a) <= 1e-9 * (1.0 + std::abs(batch.samples[i].a)));
    RC_ASSERT(got[i].risk == batch.samples[i].risk);
  }
  RC_ASSERT(tr.summary().segments == batch.summary.segments);
  RC_ASSERT(tr.summary().steps == batch.summary.steps);
  RC_ASSERT(std::abs(tr.position() - batch.samples.back().x) < 1e-12);
}
