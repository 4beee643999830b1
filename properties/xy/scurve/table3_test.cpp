// Tab. 3 of the thesis, digit for digit (typed from seed-003.md §5.2), and the exact columns
// (the core's integrator) against the closed forms A = 0.2 n, V = 0.1 n^2, P = 0.2 n^3 / 6.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "models/xy/scurve/table3.hpp"

namespace {

struct Printed {
  const char *jerk, *accel, *velocity, *position, *rounded;
};

// seed-003.md §5.2 Tab. 3 "Tabulka pro aproximaci S-krivky", verbatim.
constexpr std::array<Printed, 16> kTab3{{
    {"0", "0", "0,0", "0,0", "0"},         {"0,2", "0,2", "0,3", "0,4", "0"},
    {"0,2", "0,4", "0,8", "1,5", "1"},     {"0,2", "0,6", "1,5", "3,3", "2"},
    {"0,2", "0,8", "2,4", "6,1", "2"},     {"0,2", "1", "3,5", "10,2", "4"},
    {"0,2", "1,2", "4,8", "15,6", "5"},    {"0,2", "1,4", "6,3", "22,6", "6"},
    {"0,2", "1,6", "8,0", "31,5", "8"},    {"0,2", "1,8", "9,9", "42,3", "10"},
    {"0,2", "2", "12,0", "55,3", "12"},    {"0,2", "2,2", "14,3", "70,8", "14"},
    {"0,2", "2,4", "16,8", "88,8", "17"},  {"0,2", "2,6", "19,5", "109,6", "20"},
    {"0,2", "2,8", "22,4", "133,5", "22"}, {"0,2", "3", "25,5", "160,5", "26"},
}};

TEST(ScurveTable3, ThesisColumnsDigitForDigit) {
  const auto rows = ap::model::xy_scurve::table3_rows();
  ASSERT_EQ(rows.size(), kTab3.size());
  for (std::size_t n = 0; n < rows.size(); ++n) {
    EXPECT_EQ(rows[n].n, static_cast<int>(n));
    EXPECT_EQ(rows[n].jerk, kTab3[n].jerk) << n;
    EXPECT_EQ(rows[n].accel, kTab3[n].accel) << n;
    EXPECT_EQ(rows[n].velocity, kTab3[n].velocity) << n;
    EXPECT_EQ(rows[n].position, kTab3[n].position) << n;
    EXPECT_EQ(rows[n].rounded, kTab3[n].rounded) << n;
  }
}

TEST(ScurveTable3, ThesisRecurrenceClosedForm) {
  // seed §5.2: V_n = 0.1 n^2 + 0.2 n, i.e. in 1/30: 3 n^2 + 6 n; A_n = 0.2 n = 6 n / 30.
  for (const auto& r : ap::model::xy_scurve::table3_rows(40)) {
    const int64_t n = r.n;
    EXPECT_EQ(r.a30, 6 * n);
    EXPECT_EQ(r.v30, 3 * n * n + 6 * n);
  }
}

TEST(ScurveTable3, CoreIntegratorIsTheExactSolution) {
  // The exact constant-jerk solution with J = 0.2 (the core's unit u = 0.2): A = 0.2 n
  // (a = n), V = 0.1 n^2 (v2 = n^2), P = 0.2 n^3 / 6 (p6 = n^3).
  for (const auto& r : ap::model::xy_scurve::table3_rows(40)) {
    const int64_t n = r.n;
    EXPECT_EQ(r.exact_a, n);
    EXPECT_EQ(r.exact_v2, n * n);
    EXPECT_EQ(r.exact_p6, n * n * n);
  }
  const auto rows = ap::model::xy_scurve::table3_rows();
  EXPECT_EQ(rows[15].exact_velocity, "22,5");      // 0.1 * 15^2
  EXPECT_EQ(rows[15].exact_position, "112,5000");  // 0.2 * 15^3 / 6
  EXPECT_EQ(rows[1].exact_position, "0,0333");     // 0.2 / 6
  EXPECT_EQ(rows[5].exact_accel, "1");
}

TEST(ScurveTable3, ReportPrintsBothAndTheDrift) {
  const std::string rep = ap::model::xy_scurve::table3_report();
  // Row 15: the thesis's 25,5 and 160,5 beside the exact 22,5 and 112,5000, drift 0,2 * 15 = 3,0.
  EXPECT_NE(rep.find("   15   0,2      3      25,5     160,5       26 |      3      22,5  112,5000      3,0"),
            std::string::npos)
      << rep;
  EXPECT_NE(rep.find("Tab. 3"), std::string::npos);
}

}  // namespace
