#pragma once
// The table S-curve (seed-003.md §5.2 "Lookup table", §5.3.2; docs/scurve.md "Table").
//
// Sc[i] is the fraction of the target velocity at table entry i of a pure jerk-limited ramp
// (no constant-acceleration part, as the thesis's only quantitative ramp, §5.3.1), in fixed
// point with kOne = 65536 = 1.0. [D] Entry i sits at the normalised ramp time
// tau_i = (i + 1) / (N + 1), which is symmetric (tau_i + tau_{N-1-i} = 1) and never 0 or 1, so
// the first entry is a small non-zero speed (the thesis's 0.001) and the last is below 1
// (0.999). Over the first half v(tau) = 2 tau^2; the second half is built from the first as
// Sc[N-1-i] = kOne - Sc[i], so the point symmetry the thesis states holds EXACTLY, and the
// deceleration table is kOne - Sc (§5.3.2: "1 - table value").
// Ranges: 1 <= N <= 4096 (2 (i+1)^2 kOne < 2^64), values in [0, kOne], monotone.
#include <array>
#include <cstddef>
#include <cstdint>

namespace ap::xy_scurve {

inline constexpr uint32_t kOne = 65536;
inline constexpr std::size_t kThesisEntries = 50;  // seed §9: "only the first 50 interpolations"

template <std::size_t N>
struct Table {
  static_assert(N >= 1 && N <= 4096, "docs/scurve.md: 1 <= N <= 4096");
  std::array<uint32_t, N> sc{};
};

// round-half-up(kOne * 2 (i+1)^2 / (N+1)^2): the first-half value of entry i.
template <std::size_t N>
constexpr uint32_t rising_value(std::size_t i) {
  const uint64_t num = 2ULL * (i + 1) * (i + 1) * kOne;
  const uint64_t den = static_cast<uint64_t>(N + 1) * (N + 1);
  return static_cast<uint32_t>((2 * num + den) / (2 * den));
}

template <std::size_t N>
constexpr Table<N> make_table() {
  Table<N> t;
  for (std::size_t i = 0; i < N / 2; ++i) {
    t.sc[i] = rising_value<N>(i);
    t.sc[N - 1 - i] = kOne - t.sc[i];  // mirrored, never recomputed
  }
  if (N % 2 == 1) t.sc[N / 2] = kOne / 2;  // tau = 1/2 exactly: v = 2 (1/2)^2 = 1/2
  return t;
}

inline constexpr Table<kThesisEntries> kThesisTable = make_table<kThesisEntries>();

// The acceleration fraction at entry i (i < N) and the deceleration fraction (kOne - Sc[i]).
template <std::size_t N>
constexpr uint32_t accel_fraction(const Table<N>& t, std::size_t i) { return t.sc[i]; }
template <std::size_t N>
constexpr uint32_t decel_fraction(const Table<N>& t, std::size_t i) { return kOne - t.sc[i]; }

}  // namespace ap::xy_scurve
