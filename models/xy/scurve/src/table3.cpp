#include "models/xy/scurve/table3.hpp"

#include <cstdio>

#include "core/xy/scurve/integrator.hpp"

namespace ap::model::xy_scurve {
namespace {

// Tenths as the thesis prints them: "I,D".
std::string one_decimal(int64_t tenths) {
  return std::to_string(tenths / 10) + "," + std::to_string(tenths % 10);
}

// The thesis's acceleration column: integers without decimals ("1", "2"), else one ("0,2").
std::string accel_text(int64_t tenths) {
  return tenths % 10 == 0 ? std::to_string(tenths / 10) : one_decimal(tenths);
}

std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s : std::string(w - s.size(), ' ') + s; }

}  // namespace

std::vector<Table3Row> table3_rows(int last) {
  std::vector<Table3Row> rows;
  int64_t a30 = 0, v30 = 0, p30 = 0;
  constexpr int64_t kJ30 = 6;  // J = 0.2 = 6/30
  ap::xy_scurve::Exact e;         // the core's integrator with u = 0.2 (jerk +1 each tick)
  for (int n = 0; n <= last; ++n) {
    if (n > 0) {
      // The thesis's order: each update uses the values just updated (seed §5.2).
      a30 += kJ30;
      v30 += a30 + kJ30 / 2;
      p30 += v30 + a30 / 2 + kJ30 / 6;
      e = ap::xy_scurve::advance(e, +1);
    }
    Table3Row r;
    r.n = n;
    r.a30 = a30;
    r.v30 = v30;
    r.p30 = p30;
    r.jerk = n == 0 ? "0" : "0,2";
    r.accel = accel_text(a30 / 3);              // a30 / 30 in tenths = a30 / 3 (a30 = 6n)
    r.velocity = one_decimal((2 * v30 + 3) / 6);  // round-half-up(v30 / 3) tenths
    r.position = one_decimal((2 * p30 + 3) / 6);
    r.rounded = std::to_string((2 * v30 + 30) / 60);  // round-half-up(V)
    r.exact_a = e.a;
    r.exact_v2 = e.v2;
    r.exact_p6 = e.p6;
    r.exact_accel = accel_text(2 * e.a);   // A = 0.2 a -> tenths 2 a
    r.exact_velocity = one_decimal(e.v2);  // V = 0.2 v2 / 2 -> tenths v2
    const int64_t p_1e4 = (2 * e.p6 * 10000 + 30) / 60;  // P = p6 / 30, round-half-up to 4 decimals
    r.exact_position = std::to_string(p_1e4 / 10000) + "," + pad(std::to_string(p_1e4 % 10000), 4);
    for (auto& c : r.exact_position) c = c == ' ' ? '0' : c;
    rows.push_back(r);
  }
  return rows;
}

std::string table3_report() {
  std::string out;
  out += "Tab. 3 \"Tabulka pro aproximaci S-krivky\" (seed-003.md 5.2), J = 0,2, dt = 1\n";
  out += "left: the thesis's recurrence (updated-value order), exact in 1/30, printed as in the thesis\n";
  out += "right: the core's exact constant-jerk integrator (core/xy/scurve advance()), A = 0,2n, V = 0,1n^2, P = 0,2n^3/6\n\n";
  out += "    n  jerk  accel  velocity  position  rounded |  accel  velocity  position  v drift\n";
  for (const auto& r : table3_rows()) {
    const int64_t drift_tenths = (2 * r.v30 + 3) / 6 - r.exact_v2;  // thesis V - exact V, in tenths (= 2n)
    out += pad(std::to_string(r.n), 5) + pad(r.jerk, 6) + pad(r.accel, 7) + pad(r.velocity, 10) + pad(r.position, 10) +
           pad(r.rounded, 9) + " |" + pad(r.exact_accel, 7) + pad(r.exact_velocity, 10) + pad(r.exact_position, 10) +
           pad(one_decimal(drift_tenths), 9) + "\n";
  }
  out += "\nThe thesis's velocity exceeds the exact solution by 0,2n (V_n = 0,1n^2 + 0,2n): the biased update order\n";
  out += "(seed-003.md 11.2). The core integrates with the old values and matches the exact solution.\n";
  return out;
}

}  // namespace ap::model::xy_scurve
