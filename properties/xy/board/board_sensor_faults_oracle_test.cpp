// The board's I2C sensor fault handling against an independent reference of docs/sensors.md's
// rules (models/xy/sensor_faults), compared EVERY tick: random interleavings of good readings,
// scattered misses of either sensor, NoConversionYet periods, outages long enough to go Lost
// (a part off the bus, a stuck bus), recoveries with a new rate or temperature, misses right
// after a recovery, the PC clearing the fault, a foreign part. Each tick both sensors' states,
// the FAULT code, and the temperature and rotation subscribers (in the echo of a frame sent
// that tick) must equal the model's.
//
// The rig (board_rig.hpp) puts the TMP117 and ICM-20789 device models on the simulated bus;
// the model is told only what the harness did to them (how the bus answers each part, the
// identity, the rate code, what Temp_Result holds at a read), never anything of the board.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "sim/xy/rig/board_rig.hpp"
#include "models/xy/sensor_faults/sensor_faults.hpp"
#include "protocol/xy/codec/subscribers.hpp"

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;
using C = xy_codec::CommandId;
using Sub = xy_codec::SubscriberId;
namespace sf = ap::model::xy_sensor_faults;

namespace {

// The identities the datasheets give (docs/sensors.md): TMP117 Device_ID 0x0117 (SNOSD82D
// §8), ICM-20789 WHO_AM_I 0x03 (DS-000169); the foreign ones are any other part's.
constexpr std::uint16_t kTmpId = 0x0117, kForeignTmpId = 0x0118;
constexpr std::uint8_t kWhoAmI = 0x03, kForeignWhoAmI = 0x12;
// Temp_Result's reset code (SNOSD82D §8.1.1): the driver's NoConversionYet.
constexpr std::uint16_t kResultReset = 0x8000;

// ---- The script ---------------------------------------------------------------------------

enum class Kind : std::uint8_t {
  Good,          // n ticks, both parts on a healthy bus
  Noise,         // n ticks, each gyro tick / TMP117 read tick missing with a chance (seeded)
  GyroBlip,      // the gyro off the bus for n (< 10) ticks: scattered misses
  GyroOutage,    // the gyro off for n ticks (>= 10: Lost), the rate changed meanwhile; back
                 // until it is configured again, then off for k ticks right after the recovery
  TempBlip,      // the TMP117 off the bus over the next n (1..2) read ticks
  TempOutage,    // the TMP117 off for n ticks, the temperature changed meanwhile; back until
                 // configured again, then off over the next k read ticks
  NoConversion,  // the next read finds Temp_Result at its reset code
  StuckBus,      // every transaction fails with `status` for n ticks
  Rate,          // the platform turns at `code` from now
  Temp,          // the board's temperature is `mc` from the next conversion period
  Clear,         // the PC sends `clear`
  Identity,      // the gyro (which = 0) or TMP117 (which = 1) becomes foreign or genuine
};

struct Episode {
  Kind kind = Kind::Good;
  int n = 1;
  int k = 0;
  std::int16_t code = 0;
  std::int32_t mc = 0;
  xy_i2c::Status status = xy_i2c::Status::BusError;
  std::uint64_t seed = 0;
  int gyro_pct = 0, temp_pct = 0;
  int which = 0;
  bool genuine = true;
};

const char* name_of(Kind k) {
  switch (k) {
    case Kind::Good:
      return "Good";
    case Kind::Noise:
      return "Noise";
    case Kind::GyroBlip:
      return "GyroBlip";
    case Kind::GyroOutage:
      return "GyroOutage";
    case Kind::TempBlip:
      return "TempBlip";
    case Kind::TempOutage:
      return "TempOutage";
    case Kind::NoConversion:
      return "NoConversion";
    case Kind::StuckBus:
      return "StuckBus";
    case Kind::Rate:
      return "Rate";
    case Kind::Temp:
      return "Temp";
    case Kind::Clear:
      return "Clear";
    case Kind::Identity:
      return "Identity";
  }
  return "?";
}

std::ostream& operator<<(std::ostream& os, const Episode& e) {
  os << name_of(e.kind) << "{n=" << e.n << " k=" << e.k << " code=" << e.code << " mc=" << e.mc
     << " status=" << static_cast<int>(e.status) << " seed=" << e.seed << " pct=" << e.gyro_pct << "/" << e.temp_pct
     << " which=" << e.which << " genuine=" << e.genuine << "}";
  return os;
}

struct Start {
  bool tmp_present = true, gyro_present = true;
  std::int16_t code = 0;
  std::int32_t mc = 25000;
};

std::ostream& operator<<(std::ostream& os, const Start& s) {
  return os << "Start{tmp=" << s.tmp_present << " gyro=" << s.gyro_present << " code=" << s.code << " mc=" << s.mc
            << "}";
}

// ---- Generators -----------------------------------------------------------------------------

// Any rate code, often a moderate one; never 0 where a test needs a sample that moves the angle.
rc::Gen<std::int16_t> gen_code() {
  return rc::gen::weightedOneOf<std::int16_t>({
      {3, rc::gen::inRange<std::int16_t>(-32768, 32767)},
      {3, rc::gen::inRange<std::int16_t>(-3000, 3001)},
      {1, rc::gen::element<std::int16_t>(-32768, 32767, 0, 1, -1, 131, -131)},
  });
}
// A code of at least 1 °/s (131 LSB at ±250 °/s, DS-000169) in magnitude: one tick of it
// integrated more or less moves the angle by at least 1 m°, so a stale sample is visible.
rc::Gen<std::int16_t> gen_moving_code() {
  return rc::gen::map(
      rc::gen::pair(rc::gen::inRange<std::int16_t>(131, 32767), rc::gen::arbitrary<bool>()),
      [](const std::pair<std::int16_t, bool>& p) { return static_cast<std::int16_t>(p.second ? -p.first : p.first); });
}
// A temperature the TMP117 reads exactly: a multiple of 125 m°C is 16 LSB of 7.8125 m°C
// (SNOSD82D), so the device model's nearest code and the driver's conversion are both exact.
// From -255.875 °C to 255.875 °C: below the wire's -99.999 °C too (clamped).
rc::Gen<std::int32_t> gen_mc() {
  return rc::gen::weightedOneOf<std::int32_t>({
      {3, rc::gen::map(rc::gen::inRange<std::int32_t>(-2047, 2048), [](std::int32_t k) { return k * 125; })},
      {3, rc::gen::map(rc::gen::inRange<std::int32_t>(-80, 400), [](std::int32_t k) { return k * 125; })},
      {1, rc::gen::element<std::int32_t>(-99875, -100000, -120000, 255875, -255875)},
  });
}
rc::Gen<xy_i2c::Status> gen_status() {
  return rc::gen::element(xy_i2c::Status::AddressNack, xy_i2c::Status::DataNack, xy_i2c::Status::BusError);
}

Episode ep(Kind kind) {
  Episode e;
  e.kind = kind;
  return e;
}

rc::Gen<Episode> gen_good(int lo, int hi) {
  return rc::gen::map(rc::gen::inRange(lo, hi + 1), [](int n) {
    auto e = ep(Kind::Good);
    e.n = n;
    return e;
  });
}
rc::Gen<Episode> gen_gyro_blip() {
  return rc::gen::map(rc::gen::inRange(1, 10), [](int n) {
    auto e = ep(Kind::GyroBlip);
    e.n = n;
    return e;
  });
}
rc::Gen<Episode> gen_temp_blip() {
  return rc::gen::map(rc::gen::inRange(1, 3), [](int n) {
    auto e = ep(Kind::TempBlip);
    e.n = n;
    return e;
  });
}
rc::Gen<Episode> gen_gyro_outage() {
  return rc::gen::map(rc::gen::tuple(rc::gen::inRange(10, 451), rc::gen::inRange(0, 10), gen_code()),
                      [](const std::tuple<int, int, std::int16_t>& t) {
                        auto e = ep(Kind::GyroOutage);
                        e.n = std::get<0>(t);
                        e.k = std::get<1>(t);
                        e.code = std::get<2>(t);
                        return e;
                      });
}
rc::Gen<Episode> gen_temp_outage() {
  return rc::gen::map(rc::gen::tuple(rc::gen::inRange(500, 3501), rc::gen::inRange(0, 3), gen_mc()),
                      [](const std::tuple<int, int, std::int32_t>& t) {
                        auto e = ep(Kind::TempOutage);
                        e.n = std::get<0>(t);
                        e.k = std::get<1>(t);
                        e.mc = std::get<2>(t);
                        return e;
                      });
}
rc::Gen<Episode> gen_noise() {
  return rc::gen::map(rc::gen::tuple(rc::gen::inRange(1, 1501), rc::gen::arbitrary<std::uint64_t>(),
                                     rc::gen::inRange(0, 31), rc::gen::inRange(0, 61)),
                      [](const std::tuple<int, std::uint64_t, int, int>& t) {
                        auto e = ep(Kind::Noise);
                        e.n = std::get<0>(t);
                        e.seed = std::get<1>(t);
                        e.gyro_pct = std::get<2>(t);
                        e.temp_pct = std::get<3>(t);
                        return e;
                      });
}
rc::Gen<Episode> gen_stuck_bus() {
  return rc::gen::map(rc::gen::pair(rc::gen::inRange(1, 1201), gen_status()), [](const std::pair<int, xy_i2c::Status>& p) {
    auto e = ep(Kind::StuckBus);
    e.n = p.first;
    e.status = p.second;
    return e;
  });
}
rc::Gen<Episode> gen_rate() {
  return rc::gen::map(gen_code(), [](std::int16_t c) {
    auto e = ep(Kind::Rate);
    e.code = c;
    return e;
  });
}
rc::Gen<Episode> gen_temp() {
  return rc::gen::map(gen_mc(), [](std::int32_t mc) {
    auto e = ep(Kind::Temp);
    e.mc = mc;
    return e;
  });
}
rc::Gen<Episode> gen_identity() {
  return rc::gen::map(rc::gen::pair(rc::gen::inRange(0, 2), rc::gen::arbitrary<bool>()),
                      [](const std::pair<int, bool>& p) {
                        auto e = ep(Kind::Identity);
                        e.which = p.first;
                        e.genuine = p.second;
                        return e;
                      });
}

rc::Gen<Episode> gen_any_episode() {
  return rc::gen::weightedOneOf<Episode>({
      {6, gen_good(1, 600)},
      {3, gen_noise()},
      {5, gen_gyro_blip()},
      {3, gen_gyro_outage()},
      {5, gen_temp_blip()},
      {2, gen_temp_outage()},
      {2, rc::gen::just(ep(Kind::NoConversion))},
      {2, gen_stuck_bus()},
      {4, gen_rate()},
      {3, gen_temp()},
      {2, rc::gen::just(ep(Kind::Clear))},
      {1, gen_identity()},
  });
}

// ---- The harness: one board on the rig, the model beside it -------------------------------

class Harness {
 public:
  explicit Harness(const Start& s) {
    rate_ = s.code;
    chip_mc_ = s.mc;
    tmp_present_ = s.tmp_present;
    gyro_present_ = s.gyro_present;
    apply_world();
    rig_.tmp117.chip.set_temperature_mc(chip_mc_);
    rig_.boot();
    model_.boot(world(false));
    (void)compare("boot");
  }

  // What the script reached, by the model's account (for the property's classification).
  struct Seen {
    bool gyro_lost = false, temperature_lost = false, gyro_back = false, temperature_back = false;
    bool foreign = false, cleared = false, relatched = false;
  };

  const sf::Board& model() const { return model_; }
  const Seen& seen() const { return seen_; }
  std::uint64_t ticks() const { return model_.ticks(); }
  const std::string& failure() const { return failure_; }
  bool failed() const { return !failure_.empty(); }

  void set_gyro_present(bool p) { gyro_present_ = p; }
  void set_tmp_present(bool p) { tmp_present_ = p; }
  void set_bus(std::optional<xy_i2c::Status> s) { bus_ = s; }
  void set_rate(std::int16_t c) { rate_ = c; }
  // The sensor measures `mc` from the next conversion period on: applied right after the
  // next read tick, so the conversion that ends 125 ms into the period (SNOSD82D Table 7-7:
  // 125 ms active, then standby) takes it and the read at the period's end returns it.
  void set_temperature(std::int32_t mc) { next_mc_ = mc; }
  void no_conversion_at_next_read() { no_conversion_ = true; }
  void clear_at_next_tick() { clear_ = true; }
  void set_identity(int which, bool genuine) { (which == 0 ? gyro_genuine_ : tmp_genuine_) = genuine; }

  // One tick on both; false once they disagreed (the first disagreement is kept).
  bool tick() {
    if (failed()) return false;
    const bool read_tick = (ticks() + 1) % sf::kTemperatureReadPeriod == 0;
    apply_world();
    const bool reset_code = read_tick && no_conversion_;
    if (reset_code) rig_.tmp117.chip.set_result_code(kResultReset);
    xy_frame::SubscriberSlots s{};
    s[0] = {Sub::TemperatureMc, 0};
    s[1] = {Sub::RotationMdeg, 0};
    rig_.tx.clear();
    rig_.send(clear_ ? C::ClearFault : C::Nop, 0, C::Nop, 0, s);
    rig_.tick();
    const bool cleared = clear_;
    if (clear_) model_.clear_fault();
    clear_ = false;
    const sf::State gyro_was = model_.gyro_state(), temperature_was = model_.temperature_state();
    model_.tick(world(reset_code));
    note(gyro_was, temperature_was, cleared);
    if (read_tick) {
      no_conversion_ = false;
      if (next_mc_) {
        chip_mc_ = *next_mc_;
        next_mc_.reset();
        rig_.tmp117.chip.set_temperature_mc(chip_mc_);
      }
    }
    return compare("tick");
  }
  bool ticks(int n) {
    for (int i = 0; i < n; ++i) {
      if (!tick()) return false;
    }
    return true;
  }

 private:
  void apply_world() {
    rig_.tmp117.present = tmp_present_;
    rig_.gyro.present = gyro_present_;
    if (bus_ != rig_.bus_fault) {
      if (bus_) {
        rig_.fail_bus(*bus_);
      } else {
        rig_.heal_bus();
      }
    }
    rig_.gyro.chip.set_rate_code(rate_);
    rig_.gyro.chip.set_who_am_i(gyro_genuine_ ? kWhoAmI : kForeignWhoAmI);
    rig_.tmp117.chip.set_device_id(tmp_genuine_ ? kTmpId : kForeignTmpId);
  }

  void note(sf::State gyro_was, sf::State temperature_was, bool cleared) {
    const sf::State g = model_.gyro_state(), t = model_.temperature_state();
    seen_.gyro_lost |= g == sf::State::Lost;
    seen_.temperature_lost |= t == sf::State::Lost;
    seen_.gyro_back |= gyro_was == sf::State::Lost && g == sf::State::Ok;
    seen_.temperature_back |= temperature_was == sf::State::Lost && t == sf::State::Ok;
    seen_.foreign |= g == sf::State::Foreign || t == sf::State::Foreign;
    seen_.cleared |= cleared && (g == sf::State::Lost || t == sf::State::Lost);
    seen_.relatched |= seen_.cleared && model_.fault_code() != 0;
  }

  static sf::Answer answer_of(xy_i2c::Status s) {
    switch (s) {
      case xy_i2c::Status::Ok:
        return sf::Answer::Ok;
      case xy_i2c::Status::AddressNack:
        return sf::Answer::AddressNack;
      case xy_i2c::Status::DataNack:
        return sf::Answer::DataNack;
      default:
        return sf::Answer::BusError;
    }
  }

  // What the harness did to the parts, in the model's terms: a stuck bus fails every
  // transaction its way, an absent part does not acknowledge its address.
  sf::World world(bool reset_code) const {
    sf::World w;
    const auto answer = [&](bool present) {
      if (bus_) return answer_of(*bus_);
      return present ? sf::Answer::Ok : sf::Answer::AddressNack;
    };
    w.temperature.answer = answer(tmp_present_);
    w.temperature.genuine = tmp_genuine_;
    w.temperature.result_mc = reset_code ? std::nullopt : std::optional<std::int32_t>(chip_mc_);
    w.gyro.answer = answer(gyro_present_);
    w.gyro.genuine = gyro_genuine_;
    w.gyro.code = rate_;
    return w;
  }

  static sf::State state_of(SensorState s) {
    switch (s) {
      case SensorState::Ok:
        return sf::State::Ok;
      case SensorState::Lost:
        return sf::State::Lost;
      case SensorState::Foreign:
        return sf::State::Foreign;
      case SensorState::Unwired:
        break;
    }
    return static_cast<sf::State>(0xFF);  // never the model's: the board is wired here
  }
  static const char* text(sf::State s) {
    switch (s) {
      case sf::State::Ok:
        return "Ok";
      case sf::State::Lost:
        return "Lost";
      case sf::State::Foreign:
        return "Foreign";
    }
    return "Unwired";
  }

  bool compare(const char* when) {
    std::ostringstream os;
    const auto& b = *rig_.board;
    const auto check = [&](const char* what, std::int64_t board, std::int64_t model) {
      if (board != model) os << " " << what << ": board " << board << ", model " << model << ";";
    };
    if (state_of(b.sensors().temperature) != model_.temperature_state()) {
      os << " TMP117 state: board " << text(state_of(b.sensors().temperature)) << ", model "
         << text(model_.temperature_state()) << ";";
    }
    if (state_of(b.sensors().gyro) != model_.gyro_state()) {
      os << " gyro state: board " << text(state_of(b.sensors().gyro)) << ", model " << text(model_.gyro_state()) << ";";
    }
    check("fault code", b.fault_code(), model_.fault_code());
    check("temperature_mc()", b.temperature_mc(), model_.temperature_mc());
    check("rotation_mdeg()", b.rotation_mdeg(), model_.rotation_mdeg());
    if (std::string(when) == "tick") {
      const auto e = rig_.last_echo();
      if (!e) {
        os << " no echo;";
      } else {
        check("temperature subscriber", e->subs[0].data, model_.temperature_subscriber());
        check("rotation subscriber", e->subs[1].data, model_.rotation_mdeg());
      }
    }
    if (!os.str().empty()) failure_ = std::string(when) + " " + std::to_string(ticks()) + ":" + os.str();
    return failure_.empty();
  }

  Rig rig_;
  sf::Board model_;
  bool tmp_present_ = true, gyro_present_ = true;
  std::optional<xy_i2c::Status> bus_;
  std::int32_t chip_mc_ = 25000;
  std::optional<std::int32_t> next_mc_;
  bool no_conversion_ = false;
  bool clear_ = false;
  std::int16_t rate_ = 0;
  bool gyro_genuine_ = true, tmp_genuine_ = true;
  std::string failure_;
  Seen seen_;
};

// Ticks until `done` or `limit` ticks; false on a disagreement.
template <class F>
bool until(Harness& h, int limit, F done) {
  for (int i = 0; i < limit && !done(); ++i) {
    if (!h.tick()) return false;
  }
  return true;
}

// Ticks until `reads` more TMP117 read ticks (ticks() % 250 == 0) have passed.
bool over_reads(Harness& h, int reads) {
  for (int r = 0; r < reads; ++r) {
    if (!h.tick()) return false;
    if (!until(h, static_cast<int>(sf::kTemperatureReadPeriod),
               [&] { return h.ticks() % sf::kTemperatureReadPeriod == 0; })) {
      return false;
    }
  }
  return true;
}

// A small deterministic generator for the Noise episode's per-tick choices (SplitMix64).
struct SplitMix {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  bool chance(int pct) { return static_cast<int>(next() % 100) < pct; }
};

bool run(Harness& h, const Episode& e) {
  // Every episode but the instant ones starts from both parts on a healthy bus.
  const auto healthy = [&] {
    h.set_bus(std::nullopt);
    h.set_gyro_present(true);
    h.set_tmp_present(true);
  };
  switch (e.kind) {
    case Kind::Good:
      healthy();
      return h.ticks(e.n);
    case Kind::Noise: {
      healthy();
      SplitMix rng{e.seed};
      for (int i = 0; i < e.n; ++i) {
        h.set_gyro_present(!rng.chance(e.gyro_pct));
        const bool read_tick = (h.ticks() + 1) % sf::kTemperatureReadPeriod == 0;
        h.set_tmp_present(!(read_tick && rng.chance(e.temp_pct)));
        if (!h.tick()) return false;
      }
      healthy();
      return true;
    }
    case Kind::GyroBlip:
      healthy();
      h.set_gyro_present(false);
      if (!h.ticks(e.n)) return false;
      h.set_gyro_present(true);
      return true;
    case Kind::GyroOutage: {
      healthy();
      h.set_gyro_present(false);
      h.set_rate(e.code);
      if (!h.ticks(e.n)) return false;
      h.set_gyro_present(true);
      if (!until(h, 2 * static_cast<int>(sf::kGyroRetryPeriod),
                 [&] { return h.model().gyro_state() != sf::State::Lost; })) {
        return false;
      }
      h.set_gyro_present(false);
      if (!h.ticks(e.k)) return false;
      h.set_gyro_present(true);
      return true;
    }
    case Kind::TempBlip:
      healthy();
      h.set_tmp_present(false);
      if (!over_reads(h, e.n)) return false;
      h.set_tmp_present(true);
      return true;
    case Kind::TempOutage: {
      healthy();
      h.set_tmp_present(false);
      h.set_temperature(e.mc);
      if (!h.ticks(e.n)) return false;
      h.set_tmp_present(true);
      if (!until(h, 2 * static_cast<int>(sf::kTemperatureRetryPeriod),
                 [&] { return h.model().temperature_state() != sf::State::Lost; })) {
        return false;
      }
      h.set_tmp_present(false);
      if (!over_reads(h, e.k)) return false;
      h.set_tmp_present(true);
      return true;
    }
    case Kind::NoConversion:
      healthy();
      h.no_conversion_at_next_read();
      return over_reads(h, 1);
    case Kind::StuckBus:
      h.set_bus(e.status);
      if (!h.ticks(e.n)) return false;
      h.set_bus(std::nullopt);
      return true;
    case Kind::Rate:
      h.set_rate(e.code);
      return true;
    case Kind::Temp:
      h.set_temperature(e.mc);
      return true;
    case Kind::Clear:
      h.clear_at_next_tick();
      return h.tick();
    case Kind::Identity:
      h.set_identity(e.which, e.genuine);
      return true;
  }
  return true;
}

// Runs the script (up to a tick budget, so one case stays around a second under ASan), then
// a tail of good ticks long enough for any outage to have recovered and been read again.
void check(const Start& s, const std::vector<Episode>& script, std::uint64_t budget) {
  Harness h(s);
  RC_ASSERT(!h.failed());
  for (const Episode& e : script) {
    if (h.ticks() >= budget) break;
    if (!run(h, e)) break;
  }
  if (!h.failed()) (void)run(h, Episode{Kind::Good, 1250});
  if (h.failed()) RC_FAIL(h.failure());
  const auto& seen = h.seen();
  RC_CLASSIFY(seen.gyro_lost, "gyro Lost");
  RC_CLASSIFY(seen.gyro_back, "gyro recovered");
  RC_CLASSIFY(seen.temperature_lost, "TMP117 Lost");
  RC_CLASSIFY(seen.temperature_back, "TMP117 recovered");
  RC_CLASSIFY(seen.foreign, "a part Foreign");
  RC_CLASSIFY(seen.relatched, "cleared while Lost, latched again");
}

// Both parts on the bus at boot, or (may_be_absent) each missing at boot one time in eight.
rc::Gen<Start> gen_start(bool may_be_absent) {
  const int lo = may_be_absent ? 0 : 1;
  return rc::gen::map(rc::gen::tuple(rc::gen::inRange(lo, 8), rc::gen::inRange(lo, 8), gen_code(), gen_mc()),
                      [](const std::tuple<int, int, std::int16_t, std::int32_t>& t) {
                        Start s;
                        s.tmp_present = std::get<0>(t) != 0;
                        s.gyro_present = std::get<1>(t) != 0;
                        s.code = std::get<2>(t);
                        s.mc = std::get<3>(t);
                        return s;
                      });
}

}  // namespace

// Any interleaving of everything the bus can do to the two parts (docs/sensors.md "What the
// board does on an I2C error", "On the board" and its decisions), sometimes with a part
// missing at boot: every tick, states, FAULT code and both subscribers as the model says.
RC_GTEST_PROP(BoardSensorFaultsOracle, AnyInterleavingMatchesTheDocumentedRulesEveryTick, ()) {
  const Start s = *gen_start(true);
  const auto script = *rc::gen::container<std::vector<Episode>>(gen_any_episode());
  check(s, script, 6000);
}

// Misses scattered between good readings (docs/sensors.md: 3 TMP117 periods / 10 gyro reads
// IN A ROW latch; "In a row means in a row"): any number of them, never a latch; each blip
// is followed by at least one good reading of the sensor it hit.
RC_GTEST_PROP(BoardSensorFaultsOracle, ScatteredMissesBetweenGoodReadingsNeverLatch, ()) {
  const Start s = *gen_start(false);
  const auto blip = rc::gen::weightedOneOf<Episode>({
      {4, gen_temp_blip()},
      {4, gen_gyro_blip()},
      {2, rc::gen::just(ep(Kind::NoConversion))},
      {2, gen_rate()},
      {2, gen_temp()},
  });
  const auto pairs = *rc::gen::inRange<std::size_t>(0, 10);  // a few thousand ticks
  auto script = *rc::gen::container<std::vector<std::vector<Episode>>>(
      pairs, rc::gen::map(rc::gen::pair(blip, gen_good(1, 300)), [](const std::pair<Episode, Episode>& p) {
        return std::vector<Episode>{p.first, p.second};
      }));
  // At least three TMP117 misses, each between good readings, wherever they fall in the script:
  // three that latched would be three EVER, not three in a row.
  for (int i = 0; i < 3; ++i) {
    const auto miss =
        *rc::gen::weightedOneOf<Episode>({{3, gen_temp_blip()}, {1, rc::gen::just(ep(Kind::NoConversion))}});
    const auto at = *rc::gen::inRange<std::size_t>(0, script.size() + 1);
    script.insert(script.begin() + static_cast<std::ptrdiff_t>(at), std::vector<Episode>{miss, *gen_good(1, 300)});
  }
  std::vector<Episode> flat;
  for (const auto& pair : script) {
    // A TMP117 miss ends at a read tick; one read period of good ticks after it makes sure a
    // good reading follows before anything else happens.
    flat.push_back(pair[0]);
    if (pair[0].kind == Kind::TempBlip || pair[0].kind == Kind::NoConversion) {
      flat.push_back(Episode{Kind::Good, static_cast<int>(sf::kTemperatureReadPeriod)});
    }
    flat.push_back(pair[1]);
  }
  Harness h(s);
  RC_ASSERT(!h.failed());
  for (const Episode& e : flat) {
    if (!run(h, e)) break;
  }
  if (h.failed()) RC_FAIL(h.failure());
  // The model, from the docs, says scattered misses never latch; the board agreed every tick.
  RC_ASSERT(h.model().temperature_state() == sf::State::Ok);
  RC_ASSERT(h.model().gyro_state() == sf::State::Ok);
  RC_ASSERT(h.model().fault_code() == 0);
}

// After a Lost gyro is configured again, the rotation continues from where it stopped and
// integrates nothing from before the outage ("The held sample is reset to 0"): misses right
// after the recovery, before any good read, integrate 0. The rate before the outage moves the
// angle by at least 1 m° per tick, so a stale sample shows at once.
RC_GTEST_PROP(BoardSensorFaultsOracle, AfterAGyroRecoveryNoSampleFromBeforeTheOutageIsIntegrated, ()) {
  Start s = *gen_start(false);
  s.code = *gen_moving_code();
  const int before = *rc::gen::inRange(1, 400);
  auto outage = ep(Kind::GyroOutage);
  outage.n = *rc::gen::inRange(10, 451);
  outage.k = *rc::gen::inRange(1, 10);
  outage.code = *gen_code();
  Harness h(s);
  RC_ASSERT(!h.failed());
  bool ok = run(h, Episode{Kind::Good, before}) && run(h, outage);
  ok = ok && run(h, Episode{Kind::Good, 300});
  if (!ok) RC_FAIL(h.failure());
  RC_ASSERT(h.model().gyro_state() == sf::State::Ok);
}
