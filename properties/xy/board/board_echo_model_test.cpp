// The board core against the echo reference model (models/xy/echo, docs/echo-model.md), on
// EVERY echo: a random program of PC frames (valid, refused, outside the tables, damaged),
// ticks and changes of the board's inputs (power, BLE pins, endstops) runs on the board; the
// model is fed the same bytes and the board's sampled inputs and axis motion, and every echo
// the board sends must be the one the model predicts (seq, both statuses and their data,
// subscriber packets).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "sim/xy/rig/board_rig.hpp"
#include "sim/xy/rig/rig_sensors.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/crc16.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "models/xy/echo/board_checker.hpp"

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;
using xy_codec::CommandId;
using xy_codec::EchoStatus;
namespace em = ap::model::xy_echo;

namespace {

// A command frame with any two-digit IDs (the formatter refuses IDs outside the table, the
// board must refuse them itself: docs/protocol.md "Dispatch"), written field by field.
using Bytes = std::vector<std::uint8_t>;

void put_digits(std::string& s, std::int64_t v, int width) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%0*lld", width, static_cast<long long>(v));
  s += buf;
}
void put_data(std::string& s, std::int32_t v) {
  if (v < 0) {
    s += '-';
    put_digits(s, -static_cast<std::int64_t>(v), 5);
  } else {
    put_digits(s, v, 6);
  }
}

struct RawPart {
  std::uint8_t id = 0;
  std::int32_t data = 0;
};
struct RawFrame {
  std::uint16_t seq = 0;
  RawPart x, y;
  std::array<std::pair<std::uint8_t, std::uint8_t>, 4> subs{};
};

Bytes encode(const RawFrame& f) {
  std::string s = ">";
  put_digits(s, f.seq, 3);
  put_digits(s, f.x.id, 2);
  put_data(s, f.x.data);
  put_digits(s, f.y.id, 2);
  put_data(s, f.y.data);
  for (const auto& [id, arg] : f.subs) {
    put_digits(s, id, 2);
    put_digits(s, arg, 2);
  }
  const Bytes payload(s.begin() + 1, s.end());
  char crc[8];
  std::snprintf(crc, sizeof crc, "%04X", xy_codec::crc16(payload));
  s += crc;
  s += ';';
  return Bytes(s.begin(), s.end());
}

rc::Gen<RawPart> gen_part() {
  using rc::gen::just;
  using rc::gen::inRange;
  using rc::gen::element;
  const auto part = [](CommandId id, rc::Gen<std::int32_t> d) {
    return rc::gen::map(d, [id](std::int32_t v) { return RawPart{static_cast<std::uint8_t>(id), v}; });
  };
  return rc::gen::weightedOneOf<RawPart>({
      {6, part(CommandId::Nop, just<std::int32_t>(0))},
      {4, part(CommandId::Stop, just<std::int32_t>(0))},
      {6, part(CommandId::Jog, inRange<std::int32_t>(-2, 3))},
      {6, part(CommandId::Goto, rc::gen::oneOf(inRange<std::int32_t>(0, 205000), inRange<std::int32_t>(-2000, 2000),
                                                inRange<std::int32_t>(198000, 202000)))},
      {3, part(CommandId::Move, inRange<std::int32_t>(-60000, 60000))},
      {2, part(CommandId::Home, just<std::int32_t>(0))},
      {1, part(CommandId::SetFastSpeed, rc::gen::oneOf(inRange<std::int32_t>(1, 20000), element<std::int32_t>(2000, 625000, 700000)))},
      {1, part(CommandId::SetSlowSpeed, inRange<std::int32_t>(1, 12000))},
      {1, part(CommandId::SetAccel, rc::gen::oneOf(inRange<std::int32_t>(1, 60000), element<std::int32_t>(1, 999999)))},
      {1, part(CommandId::SetStartSpeed, inRange<std::int32_t>(1, 3000))},
      {1, part(CommandId::SetPitch, element<std::int32_t>(50, 100, 1000, 2000, 4000, 100001))},
      {1, part(CommandId::SetSteps, element<std::int32_t>(1, 200, 400, 1000, 1001))},
      {1, part(CommandId::SetMicrosteps, element<std::int32_t>(1, 3, 8, 16, 64, 256))},
      {1, part(CommandId::SetIrun, inRange<std::int32_t>(0, 32))},
      {1, part(CommandId::SetIhold, inRange<std::int32_t>(0, 32))},
      {1, part(CommandId::PeriphOff, just<std::int32_t>(0))},
      {1, part(CommandId::PeriphOn, just<std::int32_t>(0))},
      {1, part(CommandId::SaveParams, just<std::int32_t>(0))},
      {1, part(CommandId::ClearFault, just<std::int32_t>(0))},
      // Outside the tables: unknown IDs and DummyData that is not 000000.
      {1, rc::gen::construct<RawPart>(inRange<std::uint8_t>(19, 100), just<std::int32_t>(0))},
      {1, part(CommandId::Stop, inRange<std::int32_t>(1, 5))},
  });
}

rc::Gen<std::pair<std::uint8_t, std::uint8_t>> gen_slot() {
  using P = std::pair<std::uint8_t, std::uint8_t>;
  return rc::gen::weightedOneOf<P>({
      {8, rc::gen::just(P{0, 0})},
      {1, rc::gen::just(P{1, 0})},
      {1, rc::gen::just(P{3, 0})},
      {1, rc::gen::just(P{4, 0})},
      {2, rc::gen::map(rc::gen::element<std::uint8_t>(0, 1, 2, 3, 4, 5, 6, 7, 8, 19),
                       [](std::uint8_t i) { return P{8, i}; })},
      {1, rc::gen::just(P{5, 1})},
      {1, rc::gen::construct<P>(rc::gen::inRange<std::uint8_t>(0, 100), rc::gen::inRange<std::uint8_t>(0, 100))},
  });
}

struct SendFrame {
  RawFrame f;
};
struct SendDamaged {  // a valid frame with one byte replaced
  RawFrame f;
  std::size_t at = 0;
  std::uint8_t with = 0;
};
struct Ticks {
  int n = 1;
};
struct Power {
  bool usb = false, charger = false;
  std::uint16_t battery_mv = 4000;
};
struct Ble {
  bool s1 = false, s2 = true;
};
struct Endstop {
  std::size_t axis = 0;
  bool max = false;
  bool on = false;
};
// The I2C sensors (docs/sensors.md): what the TMP117 measures, the gyro's z-rate code, a part
// taken off the bus or put back, a stuck bus or a healed one.
struct Sensor {
  int kind = 0;  // 0 temperature, 1 rate, 2 TMP117 present, 3 gyro present, 4 bus
  std::int32_t value = 0;
};
using Action = std::variant<SendFrame, SendDamaged, Ticks, Power, Ble, Endstop, Sensor>;

rc::Gen<RawFrame> gen_frame() {
  return rc::gen::apply(
      [](RawPart x, RawPart y, std::pair<std::uint8_t, std::uint8_t> s0, std::pair<std::uint8_t, std::uint8_t> s3) {
        RawFrame f;
        f.x = x;
        f.y = y;
        f.subs[0] = s0;
        f.subs[3] = s3;
        return f;
      },
      gen_part(), gen_part(), gen_slot(), gen_slot());
}

rc::Gen<Action> gen_action() {
  return rc::gen::weightedOneOf<Action>({
      {12, rc::gen::map(gen_frame(), [](RawFrame f) { return Action{SendFrame{f}}; })},
      {2, rc::gen::apply([](RawFrame f, std::size_t at, std::uint8_t w) { return Action{SendDamaged{f, at, w}}; },
                         gen_frame(), rc::gen::inRange<std::size_t>(0, xy_codec::kCommandLength),
                         rc::gen::element<std::uint8_t>('0', '9', 'A', 'x', '-', ';', '>', ' '))},
      {14, rc::gen::map(rc::gen::weightedOneOf<int>({{4, rc::gen::inRange(1, 20)}, {3, rc::gen::inRange(20, 400)},
                                                      {1, rc::gen::inRange(400, 3000)}}),
                        [](int n) { return Action{Ticks{n}}; })},
      {2, rc::gen::apply([](bool u, bool c, std::uint16_t mv) { return Action{Power{u, c, mv}}; },
                         rc::gen::weightedOneOf<bool>({{5, rc::gen::just(false)}, {1, rc::gen::just(true)}}),
                         rc::gen::weightedOneOf<bool>({{5, rc::gen::just(false)}, {1, rc::gen::just(true)}}),
                         rc::gen::weightedOneOf<std::uint16_t>({{5, rc::gen::just<std::uint16_t>(4000)},
                                                                {2, rc::gen::inRange<std::uint16_t>(3200, 3500)}}))},
      {1, rc::gen::map(rc::gen::element(0, 0, 0, 0, 1, 2, 3),
                       [](int k) { return Action{Ble{(k & 1) != 0, k == 0 || k == 3}}; })},
      {2, rc::gen::apply([](std::size_t a, bool mx, bool on) { return Action{Endstop{a, mx, on}}; },
                         rc::gen::inRange<std::size_t>(0, 2), rc::gen::arbitrary<bool>(), rc::gen::arbitrary<bool>())},
      {2, rc::gen::apply([](int k, std::int32_t v) { return Action{Sensor{k, v}}; },
                         rc::gen::weightedOneOf<int>({{3, rc::gen::just(0)}, {3, rc::gen::just(1)}, {1, rc::gen::inRange(2, 5)}}),
                         rc::gen::inRange<std::int32_t>(-300000, 300000))},
  });
}

// The board and its checker, stepped together.
struct Bench {
  Rig rig;
  std::unique_ptr<em::BoardChecker> checker;
  std::uint16_t seq = 0;
  std::size_t echoes_checked = 0;
  std::vector<std::string> bad;

  explicit Bench(bool homed) {
    if (homed) {
      rig.in.encoder[0] = {25, 0, 1};  // 25 screw turns = 50 mm (eq. 7-2, 2 mm lead)
      rig.in.encoder[1] = {50, 8192, 1};
    }
    rig.boot();
    checker = std::make_unique<em::BoardChecker>(*rig.board, ap::sim::xy::boot_facts_of(rig));
  }

  void rx(const Bytes& b) {
    rig.send_raw(b);
    checker->rx(b);
  }

  void tick() {
    const std::size_t before = rig.tx.size();
    rig.tick();
    const std::span<const em::EchoBytes> sent(rig.tx.data() + before, rig.tx.size() - before);
    echoes_checked += sent.size();
    for (auto& m : checker->after_tick(sent, ap::sim::xy::sensors_of(rig))) {
      if (bad.size() < 8) bad.push_back(m);
    }
  }

  void run(const Action& act) {
    if (const auto* s = std::get_if<SendFrame>(&act)) {
      RawFrame f = s->f;
      f.seq = ++seq % 1000;
      rx(encode(f));
      tick();
    } else if (const auto* d = std::get_if<SendDamaged>(&act)) {
      RawFrame f = d->f;
      f.seq = ++seq % 1000;
      Bytes b = encode(f);
      b[d->at] = d->with;
      rx(b);
      tick();
    } else if (const auto* t = std::get_if<Ticks>(&act)) {
      for (int i = 0; i < t->n && bad.empty(); ++i) tick();
    } else if (const auto* p = std::get_if<Power>(&act)) {
      rig.in.usb = p->usb;
      rig.in.charger = p->charger;
      rig.in.battery_mv = p->battery_mv;
    } else if (const auto* b = std::get_if<Ble>(&act)) {
      rig.in.ble_status1 = b->s1;
      rig.in.ble_status2 = b->s2;
    } else if (const auto* e = std::get_if<Endstop>(&act)) {
      (e->max ? rig.in.endstop_max : rig.in.endstop_min)[e->axis] = e->on ? 1 : 0;
    } else if (const auto* z = std::get_if<Sensor>(&act)) {
      switch (z->kind) {
        case 0: rig.tmp117.chip.set_temperature_mc(z->value); break;
        case 1: rig.gyro.chip.set_rate_code(static_cast<std::int16_t>(z->value % 32768)); break;
        case 2: rig.tmp117.present = z->value >= 0; break;
        case 3: rig.gyro.present = z->value >= 0; break;
        default:
          if (z->value % 3 == 0) {
            rig.fail_bus(z->value > 0 ? xy_i2c::Status::BusError : xy_i2c::Status::DataNack);
          } else {
            rig.heal_bus();
          }
          break;
      }
    }
  }
};

std::string describe(const Action& a) {
  if (const auto* s = std::get_if<SendFrame>(&a)) {
    return "frame x=" + std::to_string(s->f.x.id) + ":" + std::to_string(s->f.x.data) + " y=" + std::to_string(s->f.y.id) +
           ":" + std::to_string(s->f.y.data);
  }
  if (const auto* d = std::get_if<SendDamaged>(&a)) return "damaged frame, byte " + std::to_string(d->at);
  if (const auto* t = std::get_if<Ticks>(&a)) return "ticks " + std::to_string(t->n);
  if (const auto* p = std::get_if<Power>(&a)) {
    return "power usb=" + std::to_string(p->usb) + " charger=" + std::to_string(p->charger) + " mV=" +
           std::to_string(p->battery_mv);
  }
  if (const auto* b = std::get_if<Ble>(&a)) return "ble " + std::to_string(b->s1) + std::to_string(b->s2);
  if (const auto* z = std::get_if<Sensor>(&a)) return "sensor " + std::to_string(z->kind) + " " + std::to_string(z->value);
  const auto& e = std::get<Endstop>(a);
  return std::string("endstop ") + (e.axis == 0 ? "x " : "y ") + (e.max ? "max " : "min ") + (e.on ? "on" : "off");
}

}  // namespace

// Every echo of a random session agrees with the model.
RC_GTEST_PROP(BoardEchoModel, EveryEchoMatchesTheModel, ()) {
  const bool homed = *rc::gen::weightedOneOf<bool>({{4, rc::gen::just(true)}, {1, rc::gen::just(false)}});
  const auto program = *rc::gen::container<std::vector<Action>>(gen_action());
  Bench b(homed);
  std::string log;
  for (const Action& a : program) {
    log += describe(a) + "\n";
    b.run(a);
    if (!b.bad.empty()) break;
  }
  for (int i = 0; i < 5 && b.bad.empty(); ++i) b.tick();
  if (!b.bad.empty()) {
    std::string all;
    for (const auto& m : b.bad) all += m + "\n";
    RC_FAIL("board disagrees with the echo model:\n" + all + "after:\n" + log);
  }
  RC_TAG(b.echoes_checked > 0);
}

// The decisions' table (docs/echo-model.md): a move standing short of its target whose way on
// is closed by an active switch is ended by the switch (ENDSTOP), also when a command of the
// same tick is refused: a refusal is its own echo and does not hide the event. Found by
// `RC_PARAMS="max_size=200 max_success=1000 seed=2020"` runs of the property above (the board
// said IDLE). X: a jog down at its start speed, then a goto 198 mm (it stops at once, short
// of the target), the max switch on, the goto again (refused: toward the active switch), a
// stop at rest.
TEST(BoardEchoModel, RefusalBesideAMoveTheSwitchEndsKeepsTheEndstop) {
  Bench b(true);
  const auto send = [&b](CommandId x, std::int32_t xd, CommandId y, std::int32_t yd) {
    RawFrame f;
    f.x = {static_cast<std::uint8_t>(x), xd};
    f.y = {static_cast<std::uint8_t>(y), yd};
    b.run(SendFrame{f});
  };
  send(CommandId::Jog, -2, CommandId::Jog, -2);
  send(CommandId::Goto, 198000, CommandId::Stop, 0);
  b.run(Endstop{0, true, true});
  send(CommandId::Goto, 198000, CommandId::SetPitch, 50);
  send(CommandId::Stop, 0, CommandId::Move, -60000);
  EXPECT_TRUE(b.bad.empty()) << (b.bad.empty() ? "" : b.bad.front());
  xy_frame::EchoFrame last{};
  ASSERT_TRUE(xy_frame::parse_echo(b.rig.tx.back(), last).ok());
  EXPECT_EQ(last.x.status, EchoStatus::EndstopHit);
  EXPECT_EQ(last.x.data, 50000);
}

// docs/protocol.md "Two frames in one cycle": two new frames whose bytes are both in the
// receive ring at one tick (a given-up frame's late copy arriving with the client's next one,
// or two senders) are taken one per tick, each answered with its own seq and its own outcome,
// and both run. Seq 1 asks X for a goto beyond the soft limit (refused), seq 2 for a move of
// +1 mm (runs). Taken in one tick, the move replaced the goto unrun: seq 1 was answered as if
// it had run, and a refusal of one showed on the other's echo. The echo model agrees tick by
// tick, and its account of each frame (the outcome oracle's ground truth) is the documented one.
TEST(BoardEchoModel, TwoNewFramesInOneTickAreTakenOnePerTick) {
  Bench b(true);
  RawFrame goto_far;
  goto_far.seq = 1;
  goto_far.x = {static_cast<std::uint8_t>(CommandId::Goto), 999999};  // soft max is 200 mm
  RawFrame move;
  move.seq = 2;
  move.x = {static_cast<std::uint8_t>(CommandId::Move), 1000};
  Bytes both = encode(goto_far);
  const Bytes second = encode(move);
  both.insert(both.end(), second.begin(), second.end());
  const std::int32_t start = b.rig.ax(ap::xy_board::Axis::X).pos;
  b.rx(both);

  b.tick();
  ASSERT_EQ(b.rig.tx.size(), 1U) << "one answer: the second frame waits in the ring";
  xy_frame::EchoFrame e{};
  ASSERT_TRUE(xy_frame::parse_echo(b.rig.tx.back(), e).ok());
  EXPECT_EQ(e.seq, 1);
  EXPECT_EQ(e.x.status, EchoStatus::CommandRefused);
  EXPECT_EQ(e.x.data, static_cast<std::int32_t>(CommandId::Goto));
  EXPECT_EQ(b.rig.board->counters().dispatched_frames, 1U);
  EXPECT_EQ(b.rig.ax(ap::xy_board::Axis::X).mode, ap::xy_axis::Mode::Idle) << "the refused goto changed nothing";
  const auto& f1 = b.checker->model().fate_this_tick();
  ASSERT_TRUE(f1.has_value());
  EXPECT_EQ(f1->frame.seq, 1);
  EXPECT_EQ(f1->refused[0], CommandId::Goto);

  b.tick();
  ASSERT_EQ(b.rig.tx.size(), 2U);
  ASSERT_TRUE(xy_frame::parse_echo(b.rig.tx.back(), e).ok());
  EXPECT_EQ(e.seq, 2);
  EXPECT_NE(e.x.status, EchoStatus::CommandRefused) << "the goto's refusal stays on its own answer";
  EXPECT_EQ(b.rig.board->counters().dispatched_frames, 2U);
  EXPECT_EQ(b.rig.ax(ap::xy_board::Axis::X).target, start + 1600) << "+1 mm = 1600 usteps (2 mm lead, 3200 usteps/rev)";
  const auto& f2 = b.checker->model().fate_this_tick();
  ASSERT_TRUE(f2.has_value());
  EXPECT_EQ(f2->frame.seq, 2);
  EXPECT_FALSE(f2->refused[0].has_value());

  for (int t = 0; t < 10; ++t) b.tick();
  EXPECT_TRUE(b.bad.empty()) << (b.bad.empty() ? "" : b.bad.front());
}
