// The board core driven by a fuzz-decoded script of events, with the safety properties of
// docs/motion.md asserted after every tick. Any violation aborts (a finding; the replay ctest
// fails on it).
// One file, longer than the others: one fuzz entry point, its script's decoder (a table of
// ops) and its custom mutator, which libFuzzer needs in the same binary and the -O2 copies of
// fuzz/xy/board/CMakeLists.txt compile with it.
//
// Script: a sequence of ops, each one byte (low nibble = op) plus arguments:
//   0-5  an intact command frame (7 argument bytes: X id, X data (2), Y id, Y data (2),
//        subscriber slot), then one tick. Most ops are frames, so the deeper states (moves,
//        parameter saves) are reached. ID bytes >= 0xF0 give IDs just past the command
//        table (see part_of): the board's callback table must refuse them itself.
//   6    a raw UART chunk: length (mod 64) then that many bytes (the custom mutator below
//        repairs the CRC of frame-shaped runs so they get past the CRC check)
//   7    wait up to (n + 1) * 8 ticks, silent link
//   8    wait up to (n + 1) * 8 ticks, the PC repeating the last valid frame every 100 ms
//   9    endstop: bit 0 axis, bit 1 min/max, bit 2 level
//   10   power: bit 0 USB, bit 1 charger, bits 2-4 battery level
//   11   BLE status pins: bits 0-1
//   12   with bit 7 clear: TMC2130 chip reset (motor supply dip) on axis bit 0;
//        with bit 7 set, an I2C sensor event (docs/sensors.md), bits 0-2:
//          0 the TMP117 measures the next 2 bytes (signed) x 8 m°C
//          1 the gyro's z-rate code is the next 2 bytes (signed)
//          2 / 3 the TMP117 / the ICM-20789 taken off the bus or put back (toggle)
//          4 the bus stuck (bits 3-4: BusError, DataNack, AddressNack) or, with 3, healed
//          5 both sensors power-cycled (TMP117 back to 0x8000 and 1 s cycles, gyro asleep)
//          6 the TMP117's Device_ID cycles 0x0117, 0x2117 (a later revision), 0x0118 (foreign)
//          7 a foreign ICM-20789 WHO_AM_I, or the true one (toggle)
//        and with bit 6 also set, then (next byte + 1) * 4 ticks that do not end when the
//        board settles: the sensors' periods (250 ms reads, 100 ms retries) pass only in time
//   13   power cut during a FRAM save: cut after 2k SPI bytes, SetAccel v, reboot
//   14   orderly shutdown, then reboot
//        (ops 13 and 14 past the reboot budget, kMaxReboots, are skipped)
//   15   encoder reading of axis bit 0: turns (signed byte), counts
// After the script, a silent wait of up to 400 ticks: every jog must end through the watchdog.
//
// A wait ends early once the board has settled (see settled()): from then on silent ticks
// only advance the clock, so running them would cost time and find nothing. The rate that
// buys matters: the gate's fuzz smoke runs this target for 10 s in the Debug asan build.
// The settle_check replay (AP_BOARD_SETTLE_CHECK) keeps the claim honest: it runs the rest
// of every wait tick by tick and aborts if a settled board changes.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "core/xy/axis/watchdog.hpp"
#include "core/xy/frame/fields.hpp"
#include "core/xy/tmc2130/fields.hpp"
#include "models/xy/echo/board_checker.hpp"
#include "models/xy/safety/board_monitor.hpp"
#include "fuzz/script_reader.hpp"
#include "sim/xy/rig/board_rig.hpp"
#include "sim/xy/rig/rig_sensors.hpp"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size)
    __attribute__((weak));

namespace {

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;
namespace tmc = ap::xy_tmc2130;

// Work bounds per input, so one long script cannot stall the run (libFuzzer grows inputs up
// to 4 KB; the gate passes no -max_len). 0.6 s of board time holds a jog and the whole
// watchdog period (0.3 s) that must end it, or an acceleration to the fast speed (0.5 s with
// the default parameters); the states of a longer move (cruise, braking, arrival) are
// reached by shorter ones. Measured: a 10 s gate-style run reaches every core/xy/board and
// core/xy/axis branch the old 12,000-tick bound reached (fuzz/README.md). A reboot (ops 13
// and 14) costs as much as ~30 ticks, and mutated scripts were full of them (15 per input on
// average), while a fifth reboot in one script reaches no state the first four cannot.
constexpr std::int64_t kMaxTicks = 600;
constexpr int kMaxReboots = 4;

[[noreturn]] void violation(const char* what, int axis, std::uint32_t tick) {
  std::fprintf(stderr, "board fuzz: safety property violated: %s (axis %d, tick %u)\n", what, axis, tick);
  std::abort();
}

[[noreturn]] void echo_disagrees(const std::string& what, std::uint32_t tick) {
  std::fprintf(stderr, "board fuzz: echo disagrees with the reference model (models/xy/echo): %s (tick %u)\n", what.c_str(), tick);
  std::abort();
}

using ap::fuzz::Reader;

std::int32_t data_in(const xy_codec::Range& r, std::uint16_t raw) {
  const std::int64_t span = static_cast<std::int64_t>(r.max) - r.min + 1;
  // Wide ranges (positions, speeds) are sampled in 4-unit steps so the travel range and the
  // speeds the step generator can reach are covered rather than mostly out-of-limit values.
  const std::int64_t v = span <= 65536 ? raw % span : (static_cast<std::int64_t>(raw) * 4) % span;
  return static_cast<std::int32_t>(r.min + v);
}

xy_frame::SubscriberSlot slot_of(std::uint8_t b) {
  const auto id = static_cast<xy_codec::SubscriberId>(b % xy_codec::kSubscribers.size());
  const auto& info = xy_codec::kSubscribers[b % xy_codec::kSubscribers.size()];
  const std::int32_t span = info.arg_range.max - info.arg_range.min + 1;
  return {id, static_cast<std::uint8_t>(info.arg_range.min + (b >> 4) % span)};
}

bool same_state(const xy_axis::State& a, const xy_axis::State& b) {
  return a.phase == b.phase && a.mode == b.mode && a.dir == b.dir && a.jog_dir == b.jog_dir && a.level == b.level &&
         a.latch_min == b.latch_min && a.latch_max == b.latch_max && a.homed == b.homed && a.pos == b.pos &&
         a.target == b.target && a.v == b.v && a.frac == b.frac;
}

#ifdef AP_BOARD_SETTLE_CHECK
constexpr bool kSettleCheck = true;
#else
constexpr bool kSettleCheck = false;
#endif

// One rig for the whole process, put back to its power-on state for every input by
// assigning each member from a pristine rig: the vectors (device logs, sent echoes) keep
// their capacity, so a short input allocates almost nothing. A fresh rig per input meant a
// fresh 32 KB FRAM model and regrown logs, and under ASan (freed memory sits in quarantine,
// new memory is filled) every input paid page faults and fills for them. The size check
// makes a new Rig member fail the build here until it is reset too.
Rig* fresh_rig() {
  static const Rig pristine;
  static Rig rig;
  static_assert(sizeof(Rig) == 34504, "a Rig member was added or changed: reset it below");
  rig.board.reset();
  rig.fram = pristine.fram;
  rig.tmc = pristine.tmc;
  // The bus keeps its attached parts (this rig's own); only its fault and log are reset.
  rig.tmp117 = pristine.tmp117;
  rig.gyro = pristine.gyro;
  rig.heal_bus();
  rig.i2c.clear_log();
  rig.in = pristine.in;
  rig.tx.clear();
  rig.motor = pristine.motor;
  rig.steps_total = pristine.steps_total;
  rig.rotor_256 = pristine.rotor_256;
  rig.kill_switch_pulls = pristine.kill_switch_pulls;
  rig.charger_enables.clear();
  rig.seq = pristine.seq;
  return &rig;
}

struct Harness {
  Rig* const rig = fresh_rig();
  // The axis safety properties (models/xy/safety), one monitor per power-up.
  model::xy_safety::BoardMonitor monitor;
  std::vector<model::xy_safety::Violation> found;
  std::int64_t ticks = 0;
  int reboots = 0;  // after the power-up in run()
  std::int64_t since_chip_reset[kAxes] = {-1, -1};
  std::array<std::uint8_t, xy_codec::kCommandLength> last_frame{};
  bool have_frame = false;

  // The reference model of every echo (docs/echo-model.md), one per power-up: it is told the
  // bytes the UART received and compares each echo the board sends with its prediction.
  std::optional<model::xy_echo::BoardChecker> checker;
  bool power_dies_this_tick = false;

  void reboot() {
    // The model's boot facts include the set this boot loads, read before the board boots.
    const xy_storage::ParameterSet stored = model::xy_echo::stored_set(rig->fram);
    (void)rig->boot();
    model::xy_echo::Boot facts = model::xy_echo::boot_facts(*rig->board, rig->in, stored);
    facts.sensors = ap::sim::xy::sensors_of(*rig);
    checker.emplace(*rig->board, facts);
    monitor = model::xy_safety::BoardMonitor{};
    monitor.booted(*rig->board);
    for (std::size_t a = 0; a < kAxes; ++a) since_chip_reset[a] = -1;
  }

  bool budget_left() const { return ticks < kMaxTicks; }

  // Bytes into the board's UART, and the same bytes to the reference model's link twin.
  void send_raw(std::span<const std::uint8_t> bytes) {
    rig->send_raw(bytes);
    checker->rx(bytes);
  }

  // One control tick, then every per-tick oracle.
  void tick() {
    ++ticks;
    Board& b = *rig->board;
    monitor.before_tick(b);
    const std::size_t sent_before = rig->tx.size();
    rig->tick();
    // Every echo of the tick against the model; not in the tick the power dies in (that echo
    // never leaves the board, and the model is replaced at the next power-up).
    if (!power_dies_this_tick) {
      const std::span<const model::xy_echo::EchoBytes> sent(rig->tx.data() + sent_before, rig->tx.size() - sent_before);
      for (const std::string& m : checker->after_tick(sent, ap::sim::xy::sensors_of(*rig))) echo_disagrees(m, b.ticks());
    }
    power_dies_this_tick = false;
    found.clear();
    monitor.after_tick(b, found);
    if (!found.empty()) violation(found.front().what, found.front().axis, found.front().tick);
    for (std::size_t a = 0; a < kAxes; ++a) check_chip_restore(a);
  }

  // A chip reset is repaired from the shadows within one check period.
  void check_chip_restore(std::size_t a) {
    if (since_chip_reset[a] < 0 || ++since_chip_reset[a] <= static_cast<std::int64_t>(kDriverCheckPeriod) + 1) return;
    const std::uint32_t reg = rig->tmc[a].chip_register(tmc::Reg::IHOLD_IRUN);
    if (tmc::field_get(reg, tmc::Field::IHOLD_IRUN_IRUN) != rig->board->store().current().run_current_cs) {
      violation("driver registers not restored after a chip reset", static_cast<int>(a), rig->board->ticks());
    }
    since_chip_reset[a] = -1;
  }

  // Settled: no received byte waits for the framer, no chip-reset repair is still being
  // watched, and each axis is at rest with no motion mode and its endstop latches already
  // holding the active endstops. Then, with no further bytes, the board hands the axes no
  // command (commands come only from frames), and xy_axis::step() from such a state with no
  // command is the identity (Edge I, docs/motion.md), whatever the endstop, block and link
  // inputs; the inputs are levels that only ops change. Silent ticks from here on only move
  // the clock, the watchdog count and the periodic driver check, which has nothing to repair.
  bool settled() const {
    const Board& b = *rig->board;
    if (b.rx_pending() != 0) return false;
    for (std::size_t a = 0; a < kAxes; ++a) {
      const xy_axis::State& s = b.axis_state(static_cast<Axis>(a));
      if (since_chip_reset[a] >= 0 || s.phase != xy_axis::Phase::Stop || s.mode != xy_axis::Mode::Idle) return false;
      if ((rig->in.endstop_min[a] != 0 && s.latch_min == 0) || (rig->in.endstop_max[a] != 0 && s.latch_max == 0)) return false;
    }
    return true;
  }

  // Up to n ticks, over before the first tick if the budget is used up, and ended as soon as
  // the board has settled.
  void wait(std::int64_t n, bool keepalive) {
    for (std::int64_t i = 0; i < n && budget_left(); ++i) {
      if (keepalive && have_frame && ticks % xy_axis::kCommandPeriodTicks == 0) send_raw(last_frame);
      tick();
      if (!settled()) continue;
      if (kSettleCheck) confirm_settled(n - i - 1);
      return;
    }
  }

  // AP_BOARD_SETTLE_CHECK only: the rest of the wait, silent and tick by tick, but at least
  // long enough for the watchdog to expire and every driver to be checked once, must leave
  // both axes exactly as they are and emit no step. The oracles keep running meanwhile.
  void confirm_settled(std::int64_t rest) {
    const Board& b = *rig->board;
    const std::array<xy_axis::State, kAxes> held{b.axis_state(Axis::X), b.axis_state(Axis::Y)};
    const std::int64_t n = std::max<std::int64_t>(rest, xy_axis::kLinkTimeoutTicks + kDriverCheckPeriod);
    for (std::int64_t i = 0; i < n; ++i) {
      tick();
      for (std::size_t a = 0; a < kAxes; ++a) {
        if (!same_state(b.axis_state(static_cast<Axis>(a)), held[a]) || rig->motor[a].steps != 0) {
          violation("a settled board changed without input", static_cast<int>(a), b.ticks());
        }
      }
    }
  }

  void frame_op(Reader& r) {
    xy_frame::CommandFrame f;
    f.seq = static_cast<std::uint16_t>(++rig->seq % xy_codec::kSeqModulo);
    f.x = axis_part(r);
    f.y = axis_part(r);
    f.subs[0] = slot_of(r.u8());
    last_frame = wire_bytes(f);
    have_frame = true;
    // Link liveness: an intact frame sent whole onto an idle link is accepted by the framer
    // in this very tick (whatever the table then makes of it).
    Board& b = *rig->board;
    const bool idle = b.rx_pending() == 0 && b.framer_pending() == 0;
    const std::uint32_t accepted = b.counters().framer.accepted_frames;
    send_raw(last_frame);
    tick();
    if (idle && b.counters().framer.accepted_frames != accepted + 1) {
      violation("an intact frame on an idle link was not accepted", -1, b.ticks());
    }
  }

  // The ID byte, then the two data bytes: one statement each, because the order in which
  // function arguments are evaluated is unspecified (gcc and clang differ), and a script
  // must decode the same in the dev (gcc) replay as in the clang fuzzer that found it.
  static xy_frame::AxisCommand axis_part(Reader& r) {
    const std::uint8_t id = r.u8();
    const std::uint16_t raw = r.u16();
    return part_of(id, raw);
  }

  // One axis part. ID bytes 0xF0..0xFF give the IDs just past the command table
  // (kCommandCount .. kCommandCount + 15) with any data: intact frames the callback table's
  // own bound check must reject. 0xE0..0xEF pick one of the commands appended after the first
  // 24 (goto_slow, move_slow, ...). The others pick one of the first 24 and data in its
  // range, as every byte below 0xE0 did when the kept reproducers were found.
  static xy_frame::AxisCommand part_of(std::uint8_t id, std::uint16_t raw) {
    constexpr std::size_t kFirstTable = 24;
    static_assert(xy_codec::kCommandCount > kFirstTable);
    if (id >= 0xF0) {
      return {static_cast<xy_codec::CommandId>(xy_codec::kCommandCount + (id & 0x0FU)), static_cast<std::int32_t>(raw)};
    }
    const std::size_t k = id >= 0xE0 ? kFirstTable + (id & 0x0FU) % (xy_codec::kCommandCount - kFirstTable) : id % kFirstTable;
    const auto& info = xy_codec::kCommands[k];
    return {info.id, data_in(info.range, raw)};
  }

  // The frame's bytes with a correct CRC, whatever its IDs (format_command would refuse an
  // ID outside the table; the board must get it and refuse it itself).
  static std::array<std::uint8_t, xy_codec::kCommandLength> wire_bytes(const xy_frame::CommandFrame& f) {
    std::array<std::uint8_t, xy_codec::kCommandLength> b{};
    const std::span<std::uint8_t> out(b);
    b[0] = static_cast<std::uint8_t>(xy_codec::kCommandStart);
    xy_frame::fields::write_digits(out, xy_codec::kSeqOffset, xy_codec::kSeqWidth, f.seq);
    xy_frame::fields::write_digits(out, xy_codec::kXIdOffset, xy_codec::kIdWidth, static_cast<std::uint32_t>(f.x.id));
    xy_frame::fields::write_data(out, xy_codec::kXDataOffset, f.x.data);
    xy_frame::fields::write_digits(out, xy_codec::kYIdOffset, xy_codec::kIdWidth, static_cast<std::uint32_t>(f.y.id));
    xy_frame::fields::write_data(out, xy_codec::kYDataOffset, f.y.data);
    for (std::size_t i = 0; i < f.subs.size(); ++i) {
      const std::size_t at = xy_codec::kSubsOffset + i * xy_codec::kSlotWidth;
      xy_frame::fields::write_digits(out, at, xy_codec::kSubIdWidth, static_cast<std::uint32_t>(f.subs[i].id));
      xy_frame::fields::write_digits(out, at + xy_codec::kSubIdWidth, xy_codec::kSubArgWidth, f.subs[i].arg);
    }
    xy_frame::fields::write_hex16(out, xy_codec::kCommandCrcOffset, xy_frame::fields::payload_crc(out, xy_codec::kCommandCrcOffset));
    b[xy_codec::kCommandEndOffset] = static_cast<std::uint8_t>(xy_codec::kEnd);
    return b;
  }

  void raw_chunk_op(Reader& r) {
    std::array<std::uint8_t, 64> chunk{};
    const std::size_t len = r.u8() % chunk.size();
    for (std::size_t i = 0; i < len; ++i) chunk[i] = r.u8();
    send_raw(std::span<const std::uint8_t>(chunk.data(), len));
    tick();
  }

  void endstop_op(std::uint8_t b) {
    auto& e = (b & 2U) != 0 ? rig->in.endstop_max : rig->in.endstop_min;
    e[b & 1U] = static_cast<std::uint8_t>((b >> 2) & 1U);
  }

  void power_op(std::uint8_t b) {
    static constexpr std::array<std::uint16_t, 8> kBattery{4000, 3400, 3350, 3300, 3299, 3200, 2800, 4200};
    rig->in.usb = (b & 1U) != 0;
    rig->in.charger = (b & 2U) != 0;
    rig->in.battery_mv = kBattery[(b >> 2) & 7U];
  }

  void ble_op(std::uint8_t b) {
    rig->in.ble_status1 = (b & 1U) != 0;
    rig->in.ble_status2 = (b & 2U) != 0;
  }

  // The sensors through their device models: any temperature and rate, parts leaving and
  // coming back, a stuck bus, power cycles and foreign parts: every branch of the board's
  // error policy, with the echo model predicting each from the models alone.
  void sensor_op(std::uint8_t b, Reader& r) {
    switch (b & 7U) {
      case 0: {
        const auto v = static_cast<std::int16_t>(r.u16());
        rig->tmp117.chip.set_temperature_mc(std::int32_t{v} * 8);
        break;
      }
      case 1: rig->gyro.chip.set_rate_code(static_cast<std::int16_t>(r.u16())); break;
      case 2: rig->tmp117.present = !rig->tmp117.present; break;
      case 3: rig->gyro.present = !rig->gyro.present; break;
      case 4: {
        static constexpr std::array<xy_i2c::Status, 3> kStuck{xy_i2c::Status::BusError, xy_i2c::Status::DataNack,
                                                          xy_i2c::Status::AddressNack};
        const unsigned k = (b >> 3) & 3U;
        if (k < kStuck.size()) {
          rig->fail_bus(kStuck[k]);
        } else {
          rig->heal_bus();
        }
        break;
      }
      case 5:
        rig->tmp117.chip.power_on_reset();
        rig->gyro.chip.power_on_reset();
        break;
      case 6: {
        // A TMP117, a later silicon revision of it (accepted), a foreign part, and round.
        const std::uint16_t id = rig->tmp117.chip.reg(ap::xy_tmp117::Reg::DeviceId);
        rig->tmp117.chip.set_device_id(id == 0x0117 ? 0x2117 : (id == 0x2117 ? 0x0118 : 0x0117));
        break;
      }
      default:
        rig->gyro.chip.set_who_am_i(rig->gyro.chip.reg(ap::xy_icm20789::reg::kWhoAmI) == 0x03 ? 0x12 : 0x03);
        break;
    }
    if ((b & 0x40U) != 0) {
      // A settled board is not settled for its sensors: this wait runs to its end.
      const std::int64_t n = (std::int64_t{r.u8()} + 1) * 4;
      for (std::int64_t i = 0; i < n && budget_left(); ++i) tick();
    }
  }

  void chip_reset_op(std::uint8_t b) {
    const std::size_t a = b & 1U;
    rig->tmc[a].power_cycle();
    since_chip_reset[a] = 0;
  }

  // Ops 13 and 14 past the reboot budget still consume their argument bytes, so the rest of
  // the script decodes as it would have.
  bool reboot_budget_left() const { return reboots < kMaxReboots; }

  void power_cut_op(Reader& r) {
    // Let bytes still queued from earlier ops be handled first, so the only FRAM write in
    // the cut tick is the one this op asks for (each tick drains up to 4 frame events, at most one new frame, from the ring).
    // Only a handled frame writes the FRAM, so the wait ends with the ring empty.
    for (std::size_t i = 0; i < kRxCapacity / kMaxEchoesPerCycle && rig->board->rx_pending() != 0 && budget_left(); ++i) tick();
    const std::size_t cut = static_cast<std::size_t>(r.u8()) * 2U;
    const std::int32_t accel = 1000 + r.u8() * 400;
    const xy_storage::ParameterSet before = rig->board->store().current();
    xy_storage::ParameterSet intended = before;
    intended.max_acceleration_um_s2 = static_cast<std::uint32_t>(accel);
    rig->fram.arm_power_cut_after(cut);
    send_raw(Rig::bytes_of(Rig::frame_of(++rig->seq, xy_codec::CommandId::SetAccel, accel, xy_codec::CommandId::Nop, 0)));
    power_dies_this_tick = true;
    tick();
    rig->fram.power_on();
    ++reboots;
    reboot();
    const xy_storage::ParameterSet& now = rig->board->store().current();
    // A torn save falls back to the last verified copy: old or new, never a mixture. The
    // step-counter flag may differ only if the save that cleared it is the torn one.
    xy_storage::ParameterSet a = now;
    a.step_counts_valid = before.step_counts_valid;
    xy_storage::ParameterSet bset = now;
    bset.step_counts_valid = intended.step_counts_valid;
    const bool never_saved = rig->board->store().sequence() == 0 && now == xy_storage::defaults();
    if (!(a == before || bset == intended || never_saved)) violation("parameters after a torn save are neither old nor new", -1, 0);
  }

  void shutdown_op() {
    (void)rig->board->shutdown();
    ++reboots;
    reboot();
  }

  void encoder_op(Reader& r) {
    const std::uint8_t b = r.u8();
    rig->in.encoder[b & 1U] = {static_cast<std::int8_t>(r.u8()), static_cast<std::uint16_t>(r.u16() % xy_axis::kEncoderCounts), 1};
  }

  void op(std::uint8_t code, Reader& r) {
    switch (code) {
      case 0: case 1: case 2: case 3: case 4: case 5: frame_op(r); break;
      case 6: raw_chunk_op(r); break;
      case 7: wait((r.u8() + 1) * 8, false); break;
      case 8: wait((r.u8() + 1) * 8, true); break;
      case 9: endstop_op(r.u8()); break;
      case 10: power_op(r.u8()); break;
      case 11: ble_op(r.u8()); break;
      case 12: {
        const std::uint8_t b = r.u8();
        if ((b & 0x80U) != 0) {
          sensor_op(b, r);
        } else {
          chip_reset_op(b);
        }
        break;
      }
      case 13:
        if (reboot_budget_left()) {
          power_cut_op(r);
        } else {
          (void)r.u16();
        }
        break;
      case 14:
        if (reboot_budget_left()) shutdown_op();
        break;
      case 15: encoder_op(r); break;
      default: break;
    }
  }

  void run(const std::uint8_t* data, std::size_t size) {
    reboot();
    Reader r{data, size};
    while (r.more() && budget_left()) op(r.u8() & 0x0F, r);
    wait(xy_axis::kLinkTimeoutTicks + 100, false);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Harness h;
  h.run(data, size);
  return 0;
}

// After the default mutation, rewrite the CRC of every frame-shaped run (three times out of
// four, so bad-CRC paths stay covered); the board's own CRC check is never bypassed.
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  if (LLVMFuzzerMutate == nullptr) return size;
  size = LLVMFuzzerMutate(data, size, max_size);
  if ((seed & 3U) == 0) return size;
  const std::span<std::uint8_t> all(data, size);
  for (std::size_t i = 0; i + ap::xy_codec::kCommandLength <= size; ++i) {
    if (data[i] != static_cast<std::uint8_t>(ap::xy_codec::kCommandStart)) continue;
    const auto f = all.subspan(i, ap::xy_codec::kCommandLength);
    ap::xy_frame::fields::write_hex16(f, ap::xy_codec::kCommandCrcOffset, ap::xy_frame::fields::payload_crc(f, ap::xy_codec::kCommandCrcOffset));
  }
  return size;
}
