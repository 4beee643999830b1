// Lead screw + carriage model (docs/mechanics.md).
#include "models/xy/mechanics/mechanics.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ap::model::xy_mechanics {

double omega_from_speed(double v, double lead) { return v / lead * 2.0 * kPi; }

double epsilon_from_accel(double a, double lead) { return a / lead * 2.0 * kPi; }

double reduced_mass(double m, double inertia_sum, double lead) {
  return m + inertia_sum * 4.0 * kPi * kPi / (lead * lead);
}

double reduced_force(double torque, double lead, double m, double f1) {
  return torque / lead * 2.0 * kPi - kG * m * f1;
}

double accel_from_torque(double torque, double lead, double m, double f1, double inertia_sum) {
  return reduced_force(torque, lead, m, f1) / reduced_mass(m, inertia_sum, lead);
}

double required_torque(double a, double lead, double m, double f1, double inertia_sum) {
  return lead * m * (a + kG * f1) / (2.0 * kPi) + a * inertia_sum * 2.0 * kPi / lead;
}

Model::Model(Params p) : p_(p) {
  if (!(p_.axis.lead > 0) || !(p_.axis.mass >= 0) || p_.axis.microsteps == 0 || !(p_.motor.step_angle_deg > 0) ||
      !(p_.axis.efficiency > 0 && p_.axis.efficiency <= 1.0) || !(p_.fit_window > 0) || !(p_.rest_gap > 0)) {
    throw std::invalid_argument("mechanics: invalid parameters");
  }
}

double Model::inertia_sum() const { return p_.motor.rotor_inertia + p_.axis.screw_inertia; }

double Model::steps_per_rev() const { return p_.motor.full_steps_per_rev() * p_.axis.microsteps; }

double Model::step_length() const { return p_.axis.lead / steps_per_rev(); }

double Model::torque_required(double a, int dir) const {
  const double along = a * static_cast<double>(dir);   // acceleration in the direction of motion
  const double m = required_torque(along, p_.axis.lead, p_.axis.mass, p_.axis.friction, inertia_sum());
  return std::abs(m) / p_.axis.efficiency;
}

double Model::torque_available(double v) const {
  const Motor& mo = p_.motor;
  const double w = std::abs(omega_from_speed(v, p_.axis.lead));   // rad/s mechanical
  const double we = mo.rotor_teeth() * w;                          // rad/s electrical
  const double z = std::hypot(mo.resistance, we * mo.inductance);
  const double current = std::min(mo.nominal_current, mo.supply_voltage / z);
  return mo.torque_derating * mo.holding_torque * current / mo.nominal_current;
}

double Model::corner_speed() const {
  const Motor& mo = p_.motor;
  const double zmax = mo.supply_voltage / mo.nominal_current;
  if (zmax <= mo.resistance) {
    return 0.0;
  }
  const double we = std::sqrt(zmax * zmax - mo.resistance * mo.resistance) / mo.inductance;
  const double w = we / mo.rotor_teeth();
  return w / (2.0 * kPi) * p_.axis.lead;
}

namespace {

Risk classify(const Params& p, double required, double available) {
  if (required > p.risk_ratio * available) {
    return Risk::lost_step;
  }
  if (required > p.warn_ratio * available) {
    return Risk::warning;
  }
  return Risk::none;
}

// At most this many points per fit: a fast axis has thousands of steps in one window; an evenly
// strided subset keeps the fit O(1) per step with no visible loss (the data are smooth).
constexpr std::size_t kMaxFitPoints = 41;

// Local quadratic least-squares fit of x(t) around t_k over points [lo, hi]: returns (v, a).
std::pair<double, double> fit(std::span<const double> t, std::span<const double> x, std::size_t k, std::size_t lo,
                              std::size_t hi, double scale) {
  const std::size_t count = hi - lo + 1;
  const std::size_t stride = (count + kMaxFitPoints - 1) / kMaxFitPoints;
  const auto n = static_cast<Eigen::Index>((count + stride - 1) / stride);
  if (n == 1) {
    return {0.0, 0.0};
  }
  // Normal equations: power sums accumulated in plain doubles (Eigen expressions per point are
  // slow in unoptimised sanitizer builds), solved as a fixed-size 3x3 system with Eigen's LDLT.
  // Times are centred on t_k and scaled by the window, so the system is well conditioned.
  double st[5] = {0, 0, 0, 0, 0};   // sum tau^p
  double sx[3] = {0, 0, 0};         // sum dx * tau^p
  for (Eigen::Index r = 0; r < n; ++r) {
    const std::size_t j = lo + static_cast<std::size_t>(r) * stride;
    const double tau = (t[j] - t[k]) / scale;
    const double dx = x[j] - x[k];
    double p = 1.0;
    for (int e = 0; e < 5; ++e) {
      st[e] += p;
      if (e < 3) {
        sx[e] += dx * p;
      }
      p *= tau;
    }
  }
  Eigen::Matrix3d ata;
  ata << st[0], st[1], st[2], st[1], st[2], st[3], st[2], st[3], st[4];
  const Eigen::Vector3d atb(sx[0], sx[1], sx[2]);
  // Eigen's closed-form fixed-size inverse: exact enough for these well-scaled systems, and
  // ~10x cheaper than a decomposition in unoptimised sanitizer builds.
  if (n >= 3) {
    Eigen::Matrix3d inv;
    bool ok = false;
    ata.computeInverseWithCheck(inv, ok);
    if (ok) {
      const Eigen::Vector3d c = inv * atb;
      return {c(1) / scale, 2.0 * c(2) / (scale * scale)};
    }
  }
  // Two points (or degenerate times): a straight line.
  Eigen::Matrix2d inv2;
  bool ok2 = false;
  ata.topLeftCorner<2, 2>().computeInverseWithCheck(inv2, ok2);
  if (!ok2) {
    return {0.0, 0.0};
  }
  const Eigen::Vector2d c = inv2 * atb.head<2>();
  return {c(1) / scale, 0.0};
}

}  // namespace

Result simulate(const Model& model, std::span<const Step> steps) {
  const Params& p = model.params();
  Result r;
  const std::size_t n = steps.size();
  r.summary.steps = n;
  r.summary.min_margin = std::numeric_limits<double>::infinity();
  if (n == 0) {
    return r;
  }
  std::vector<double> t(n);
  std::vector<double> x(n);
  double pos = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (steps[k].dir != 1 && steps[k].dir != -1) {
      throw std::invalid_argument("mechanics: step direction must be +1 or -1");
    }
    if (k > 0 && steps[k].t < steps[k - 1].t) {
      throw std::invalid_argument("mechanics: step times must not decrease");
    }
    pos += steps[k].dir * model.step_length();
    t[k] = steps[k].t;
    x[k] = pos;
  }
  const double start_dist = p.start_distance_fullsteps * p.axis.lead / p.motor.full_steps_per_rev();

  auto add = [&](double tt, double xx, double v, double a, int dir) {
    Sample s{tt, xx, v, a, model.torque_required(a, dir), model.torque_available(v), Risk::none};
    s.risk = classify(p, s.torque_required, s.torque_available);
    Summary& su = r.summary;
    su.max_speed = std::max(su.max_speed, std::abs(v));
    su.max_accel = std::max(su.max_accel, std::abs(a));
    su.max_torque_required = std::max(su.max_torque_required, s.torque_required);
    if (s.torque_required > 0) {
      su.min_margin = std::min(su.min_margin, s.torque_available / s.torque_required);
    }
    if (s.risk == Risk::warning) {
      ++su.warnings;
    } else if (s.risk == Risk::lost_step) {
      ++su.lost_step_risks;
      if (!su.first_risk_t) {
        su.first_risk_t = tt;
      }
    }
    r.samples.push_back(s);
  };

  std::size_t b = 0;
  while (b < n) {
    std::size_t e = b;
    while (e + 1 < n && steps[e + 1].dir == steps[b].dir && t[e + 1] - t[e] <= p.rest_gap) {
      ++e;
    }
    ++r.summary.segments;
    const int dir = steps[b].dir;
    const double dirf = static_cast<double>(dir);
    if (e > b) {
      // Start: from rest to the first interval's speed within start_dist.
      const double v_first = model.step_length() / std::max(t[b + 1] - t[b], 1e-12);
      add(t[b], x[b] - dir * model.step_length(), 0.0, dirf * v_first * v_first / (2.0 * start_dist), dir);
    }
    for (std::size_t k = b; k <= e; ++k) {
      std::size_t lo = k;
      std::size_t hi = k;
      while (lo > b && (t[k] - t[lo - 1] <= p.fit_window / 2 || k - lo < 2)) {
        --lo;
      }
      while (hi < e && (t[hi + 1] - t[k] <= p.fit_window / 2 || hi - k < 2)) {
        ++hi;
      }
      const auto [v, a] = fit(t, x, k, lo, hi, p.fit_window);
      add(t[k], x[k], v, a, dir);
    }
    if (e > b) {
      // Stop: from the last interval's speed to rest within start_dist.
      const double v_last = model.step_length() / std::max(t[e] - t[e - 1], 1e-12);
      add(t[e], x[e], 0.0, -dirf * v_last * v_last / (2.0 * start_dist), dir);
    }
    b = e + 1;
  }
  if (r.summary.min_margin == std::numeric_limits<double>::infinity()) {
    r.summary.min_margin = 0.0;
  }
  return r;
}

void Tracker::step(double t, int dir) {
  if (dir != 1 && dir != -1) {
    throw std::invalid_argument("mechanics: step direction must be +1 or -1");
  }
  if (!pending_.empty() && t < pending_.back().t) {
    throw std::invalid_argument("mechanics: step times must not decrease");
  }
  pending_.push_back(Step{t, dir});
  position_ += dir * model_.step_length();
}

std::vector<Sample> Tracker::take(std::size_t n) {
  if (n == 0) {
    return {};
  }
  Result r = simulate(model_, std::span<const Step>(pending_.data(), n));
  for (Sample& s : r.samples) {
    s.x += flushed_x_;
  }
  for (std::size_t i = 0; i < n; ++i) {
    flushed_x_ += pending_[i].dir * model_.step_length();
  }
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
  const Summary& c = r.summary;
  Summary& m = summary_;
  m.steps += c.steps;
  m.segments += c.segments;
  m.max_speed = std::max(m.max_speed, c.max_speed);
  m.max_accel = std::max(m.max_accel, c.max_accel);
  m.max_torque_required = std::max(m.max_torque_required, c.max_torque_required);
  if (c.max_torque_required > 0) {
    m.min_margin = any_margin_ ? std::min(m.min_margin, c.min_margin) : c.min_margin;
    any_margin_ = true;
  }
  m.warnings += c.warnings;
  m.lost_step_risks += c.lost_step_risks;
  if (!m.first_risk_t) {
    m.first_risk_t = c.first_risk_t;
  }
  return std::move(r.samples);
}

std::vector<Sample> Tracker::flush(double now) {
  const double gap = model_.params().rest_gap;
  std::size_t n = 0;   // steps [0, n) form closed segments
  for (std::size_t i = 0; i + 1 < pending_.size(); ++i) {
    if (pending_[i + 1].dir != pending_[i].dir || pending_[i + 1].t - pending_[i].t > gap) {
      n = i + 1;
    }
  }
  if (!pending_.empty() && now - pending_.back().t > gap) {
    n = pending_.size();
  }
  return take(n);
}

std::vector<Sample> Tracker::finish() { return take(pending_.size()); }

std::vector<Step> trapezoid_steps(const Model& model, double distance, double v_start, double v_max, double a,
                                  double t0) {
  if (!(a > 0) || !(v_max > 0) || v_start < 0 || v_start > v_max) {
    throw std::invalid_argument("mechanics: bad trapezoid");
  }
  const int dir = distance < 0 ? -1 : 1;
  const double d = std::abs(distance);
  const double dx = model.step_length();
  const auto n = static_cast<std::size_t>(std::llround(d / dx));
  double d_acc = (v_max * v_max - v_start * v_start) / (2.0 * a);
  double v_peak = v_max;
  if (2.0 * d_acc > d) {  // triangular
    d_acc = d / 2.0;
    v_peak = std::sqrt(a * d + v_start * v_start);
  }
  const double t_acc = (v_peak - v_start) / a;
  const double d_cruise = d - 2.0 * d_acc;
  const double total = 2.0 * t_acc + d_cruise / v_peak;
  auto t_in_acc = [&](double xx) { return (-v_start + std::sqrt(v_start * v_start + 2.0 * a * xx)) / a; };
  std::vector<Step> out;
  out.reserve(n);
  for (std::size_t i = 1; i <= n; ++i) {
    const double xx = static_cast<double>(i) * dx;
    double tt = 0.0;
    if (xx <= d_acc) {
      tt = t_in_acc(xx);
    } else if (xx <= d_acc + d_cruise) {
      tt = t_acc + (xx - d_acc) / v_peak;
    } else {
      tt = total - t_in_acc(std::max(0.0, d - xx));
    }
    out.push_back(Step{t0 + tt, dir});
  }
  return out;
}

std::string to_string(Risk r) {
  switch (r) {
    case Risk::none:
      return "none";
    case Risk::warning:
      return "warning";
    case Risk::lost_step:
      return "lost_step";
  }
  return "?";
}

}  // namespace ap::model::xy_mechanics
