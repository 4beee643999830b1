// ICM-20789 rotation properties against the exact reference (reference.hpp): any sequence of
// samples at any full scale gives the reference angle after every tick, long constant runs do
// not drift, constant rates that make whole turns land exactly where they started, and the
// driver reads any modelled rate at the nearest code.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "core/xy/icm20789/driver.hpp"
#include "core/xy/icm20789/rotation.hpp"
#include "models/xy/i2c/bus.hpp"
#include "models/xy/icm20789/device.hpp"
#include "reference.hpp"

namespace {

namespace chip = ap::xy_icm20789;
using chip::FullScale;
using chip::Rotation;
using icm_test::reference_mdeg;

rc::Gen<std::int16_t> gen_raw() {
  // The saturation codes and small rates are where wrap and remainder bugs show.
  return rc::gen::oneOf(rc::gen::arbitrary<std::int16_t>(),
                        rc::gen::element<std::int16_t>(-32768, 32767, -1, 0, 1, 131, -131),
                        rc::gen::inRange<std::int16_t>(-200, 201));
}

RC_GTEST_PROP(icm20789_props, every_tick_matches_the_exact_sum, ()) {
  const int fs = *rc::gen::inRange(0, 4);
  Rotation rot{static_cast<FullScale>(fs)};
  const auto samples = *rc::gen::container<std::vector<std::int16_t>>(gen_raw());
  std::int64_t sum = 0;
  for (const auto raw : samples) {
    rot.step(raw);
    sum += raw;
    RC_ASSERT(rot.mdeg() >= 0);
    RC_ASSERT(rot.mdeg() < 360000);
    RC_ASSERT(rot.mdeg() == reference_mdeg(sum, fs));
  }
}

RC_GTEST_PROP(icm20789_props, long_constant_runs_do_not_drift, ()) {
  const int fs = *rc::gen::inRange(0, 4);
  Rotation rot{static_cast<FullScale>(fs)};
  const auto count = *rc::gen::inRange<std::size_t>(1, 6);
  const auto segments = *rc::gen::container<std::vector<std::pair<std::int16_t, int>>>(
      count, rc::gen::pair(gen_raw(), rc::gen::inRange(1, 100000)));
  std::int64_t sum = 0;
  bool in_range = true;
  for (const auto& [raw, n] : segments) {
    for (int i = 0; i < n; ++i) {
      rot.step(raw);
      in_range = in_range && rot.mdeg() < 360000;
    }
    sum += std::int64_t{raw} * n;
    RC_ASSERT(in_range);
    RC_ASSERT(rot.mdeg() == reference_mdeg(sum, fs));
  }
}

// Rates that turn the platform by exactly t turns in T ticks: raw * T / sens = t * 360 ° * 1000 ms,
// i.e. raw * T * 10 = t * 360000 * sens10 (sensitivity in tenths, reference.hpp).
struct Turn {
  std::int16_t raw;
  std::int64_t ticks;
};

const std::vector<Turn>& whole_turn_rates(int fs) {
  static const auto table = [] {
    std::vector<std::vector<Turn>> out(4);
    for (int f = 0; f < 4; ++f) {
      for (std::int64_t turns = 1; turns <= 2; ++turns) {
        const std::int64_t total = turns * 360000 * icm_test::sensitivity_tenths(f);
        for (std::int64_t ticks = 360; ticks <= 400000; ++ticks) {
          if (total % (ticks * 10) != 0 || total / (ticks * 10) > 32767) continue;
          out[static_cast<std::size_t>(f)].push_back({static_cast<std::int16_t>(total / (ticks * 10)), ticks});
        }
      }
    }
    return out;
  }();
  return table[static_cast<std::size_t>(fs)];
}

RC_GTEST_PROP(icm20789_props, whole_turns_land_exactly_back, ()) {
  const int fs = *rc::gen::inRange(0, 4);
  const auto turn = *rc::gen::elementOf(whole_turn_rates(fs));
  const auto raw = static_cast<std::int16_t>(*rc::gen::arbitrary<bool>() ? turn.raw : -turn.raw);
  Rotation rot{static_cast<FullScale>(fs)};
  for (const auto r : *rc::gen::container<std::vector<std::int16_t>>(gen_raw())) rot.step(r);
  const auto start = rot.units();
  for (std::int64_t i = 0; i < turn.ticks; ++i) rot.step(raw);
  RC_ASSERT(rot.units() == start);
}

RC_GTEST_PROP(icm20789_props, driver_reads_the_modelled_rate, ()) {
  ap::model::xy_icm20789::Device device;
  ap::model::xy_i2c::Bus bus;
  bus.attach(device);
  chip::Driver driver{bus.port()};
  const auto fs = static_cast<FullScale>(*rc::gen::inRange(0, 4));
  RC_ASSERT(driver.configure(fs));
  const auto mdps = *rc::gen::inRange<std::int32_t>(-2'100'000, 2'100'001);
  device.set_rate_mdps(mdps);
  const auto r = driver.read_rate_z();
  RC_ASSERT(r);
  // Nearest code: |code / sens - rate| <= 1/2 LSB unless saturated.
  const auto s = chip::sensitivity(fs);
  const std::int64_t err2 = 2 * (std::int64_t{*r} * 1000 * s.den - std::int64_t{mdps} * s.num);
  const std::int64_t lsb = 1000 * s.den;
  if (*r != 32767 && *r != -32768) RC_ASSERT(err2 <= lsb && err2 >= -lsb);
  if (*r == 32767) RC_ASSERT(std::int64_t{mdps} * s.num >= (32767 * 1000 - 500) * std::int64_t{s.den});
  if (*r == -32768) RC_ASSERT(std::int64_t{mdps} * s.num <= (-32768 * 1000 + 500) * std::int64_t{s.den});
}

}  // namespace
