// Integer atan2 in millidegrees for the corner look-ahead (docs/lookahead.md "Angle").
//
// Why our own: core/ has no floating point, and the thesis's angle code is not atan2 (seed-003.md
// §6 defect (a): -atan(uy/ux) for ux < 0 maps (-1, 1) onto (1, 1)).
//
// Method (octant reduction + table + linear interpolation), all integer:
//   1. ax = |x|, ay = |y| as uint64 (so INT64_MIN is fine), lo = min, hi = max.
//   2. q = floor(lo * 2^24 / hi) in [0, 2^24] by 24-step restoring division (no 128-bit product:
//      the remainder stays < hi <= 2^63, its double < 2^64).
//   3. a = atan(q / 2^24) in micro-degrees from kAtanTableUdeg (atan(i/256), i = 0..256, rounded
//      to 1 udeg) with linear interpolation on the low 16 bits of q: a in [0, 45e6] udeg.
//   4. Octant and quadrant by exact reflections: ay > ax -> 90e6 - a; x < 0 -> 180e6 - a.
//   5. Round udeg -> mdeg half-to-even, then the sign of y. -180000 (y < 0 within 0.5 mdeg of the
//      -X axis) is reported as 180000, so the range is (-180000, 180000].
// Input range: every int64 pair except (0, 0), which has no direction (AngleStatus::NoDirection).
// Error bound (docs/lookahead.md derives it): |table| <= 0.5 udeg, chord <= 71 udeg (h = 1/256,
// max |d2 atan_deg/dt2| = 37.2 deg), interpolation rounding <= 0.5 udeg, q floor <= 3.5 udeg,
// final rounding <= 500 udeg: |atan2_mdeg - atan2| <= E = 0.6 mdeg (wrapped difference).
// Exact by construction (half-to-even rounding commutes with the reflections 90000 - a,
// 180000 - a and -a, all even offsets): the four axis directions (0, 90000, 180000, -90000), the
// diagonals (+-45000, +-135000), rotation by 90 deg adds exactly 90000 (mod 360000), mirroring
// in X negates, and scaling both inputs by k leaves q and hence the result unchanged.
// Cost: 24 shift/subtract steps, one table lookup, one 64-bit multiply.
#pragma once

#include <array>
#include <cstdint>

namespace ap::xy_lookahead {

enum class AngleStatus : uint8_t {
  Ok,
  NoDirection,  // (0, 0): the zero vector has no angle (seed-003.md §6 defect (c): thesis NaN)
};

struct Angle {
  AngleStatus status;
  int32_t mdeg;  // (-180000, 180000] when status == Ok; 0 (not an angle) when NoDirection
  [[nodiscard]] constexpr bool ok() const { return status == AngleStatus::Ok; }
};

namespace detail {

// round(atan(i / 256) * 180 / pi * 1e6), i = 0..256 (generated with Python's math.atan; the
// LookaheadAngle.TableMatchesAtan test checks every entry against std::atan).
inline constexpr std::array<int32_t, 257> kAtanTableUdeg = {
    0, 223811, 447614, 671404, 895174, 1118916, 1342624, 1566291,
    1789911, 2013475, 2236979, 2460415, 2683775, 2907054, 3130245, 3353340,
    3576334, 3799220, 4021990, 4244639, 4467159, 4689544, 4911788, 5133884,
    5355825, 5577605, 5799218, 6020656, 6241914, 6462986, 6683864, 6904543,
    7125016, 7345278, 7565321, 7785140, 8004729, 8224081, 8443191, 8662052,
    8880659, 9099006, 9317086, 9534894, 9752425, 9969672, 10186630, 10403293,
    10619655, 10835712, 11051457, 11266885, 11481991, 11696770, 11911215, 12125323,
    12339087, 12552503, 12765566, 12978270, 13190611, 13402583, 13614183, 13825404,
    14036243, 14246695, 14456755, 14666419, 14875682, 15084540, 15292988, 15501022,
    15708638, 15915832, 16122599, 16328936, 16534838, 16740302, 16945323, 17149899,
    17354025, 17557697, 17760912, 17963666, 18165957, 18367779, 18569131, 18770008,
    18970408, 19170327, 19369762, 19568710, 19767169, 19965134, 20162604, 20359575,
    20556045, 20752011, 20947471, 21142421, 21336859, 21530784, 21724192, 21917080,
    22109448, 22301293, 22492612, 22683403, 22873665, 23063395, 23252592, 23441254,
    23629378, 23816963, 24004008, 24190510, 24376469, 24561882, 24746748, 24931066,
    25114835, 25298053, 25480718, 25662830, 25844388, 26025389, 26205835, 26385722,
    26565051, 26743821, 26922030, 27099677, 27276763, 27453287, 27629247, 27804643,
    27979474, 28153741, 28327442, 28500577, 28673146, 28845149, 29016584, 29187453,
    29357754, 29527487, 29696653, 29865250, 30033280, 30200743, 30367637, 30533964,
    30699723, 30864914, 31029538, 31193595, 31357085, 31520009, 31682366, 31844157,
    32005383, 32166044, 32326140, 32485672, 32644640, 32803045, 32960888, 33118169,
    33274888, 33431047, 33586646, 33741685, 33896167, 34050090, 34203457, 34356267,
    34508523, 34660224, 34811372, 34961967, 35112011, 35261505, 35410448, 35558844,
    35706691, 35853993, 36000749, 36146961, 36292630, 36437757, 36582343, 36726389,
    36869898, 37012869, 37155304, 37297204, 37438572, 37579407, 37719711, 37859486,
    37998732, 38137452, 38275647, 38413317, 38550465, 38687092, 38823199, 38958787,
    39093859, 39228415, 39362457, 39495987, 39629005, 39761514, 39893515, 40025010,
    40156000, 40286486, 40416470, 40545954, 40674940, 40803428, 40931420, 41058919,
    41185925, 41312441, 41438467, 41564006, 41689058, 41813627, 41937713, 42061318,
    42184443, 42307091, 42429263, 42550960, 42672185, 42792939, 42913223, 43033039,
    43152390, 43271276, 43389699, 43507662, 43625165, 43742211, 43858801, 43974936,
    44090620, 44205852, 44320635, 44434971, 44548861, 44662308, 44775312, 44887875,
    45000000,
};

inline constexpr uint32_t kOne = uint32_t{1} << 24;  // q = 1.0 in Q24

[[nodiscard]] constexpr uint64_t magnitude(int64_t v) {
  return v < 0 ? uint64_t{0} - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);
}

// floor(lo * 2^24 / hi) for lo <= hi, hi > 0; any uint64 values (see step 2 above).
[[nodiscard]] constexpr uint32_t ratio_q24(uint64_t lo, uint64_t hi) {
  if (lo >= hi) {
    return kOne;
  }
  uint64_t r = lo;  // invariant: r < hi
  uint32_t q = 0;
  for (int i = 0; i < 24; ++i) {
    r <<= 1;
    q <<= 1;
    if (r >= hi) {
      r -= hi;
      q |= 1u;
    }
  }
  return q;
}

// atan(q / 2^24) in udeg, q in [0, 2^24]: result in [0, 45'000'000].
[[nodiscard]] constexpr uint32_t atan_q24_udeg(uint32_t q) {
  const uint32_t idx = q >> 16;  // [0, 256]
  if (idx >= 256) {
    return static_cast<uint32_t>(kAtanTableUdeg[256]);
  }
  const int64_t lo = kAtanTableUdeg[idx];
  const int64_t step = kAtanTableUdeg[idx + 1] - lo;  // (0, 223811]
  const int64_t frac = q & 0xFFFFu;                     // [0, 65535]
  // step * frac < 2^18 * 2^16: no overflow; +2^15 rounds to nearest.
  return static_cast<uint32_t>(lo + ((step * frac + 32768) >> 16));
}

}  // namespace detail

[[nodiscard]] constexpr Angle atan2_mdeg(int64_t y, int64_t x) {
  if (x == 0 && y == 0) {
    return Angle{AngleStatus::NoDirection, 0};
  }
  const uint64_t ax = detail::magnitude(x);
  const uint64_t ay = detail::magnitude(y);
  const bool steep = ay > ax;
  uint32_t a = detail::atan_q24_udeg(steep ? detail::ratio_q24(ax, ay) : detail::ratio_q24(ay, ax));
  if (steep) {
    a = 90'000'000u - a;
  }
  if (x < 0) {
    a = 180'000'000u - a;
  }
  // udeg -> mdeg, half to even: keeps the reflections above exact.
  uint32_t m = a / 1000u;
  const uint32_t rem = a % 1000u;
  if (rem > 500u || (rem == 500u && (m & 1u) != 0u)) {
    ++m;
  }
  int32_t s = static_cast<int32_t>(m);  // [0, 180000]
  if (y < 0) {
    s = -s;
  }
  if (s == -180'000) {
    s = 180'000;
  }
  return Angle{AngleStatus::Ok, s};
}

}  // namespace ap::xy_lookahead
