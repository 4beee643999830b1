// Edges of the DDS test bus (pc/dds): domain leases refuse bad and exhausted ranges,
// a participant on an impossible domain is a typed error, an endpoint with no peer times out
// (wait_matched false, step() throws), lockstep step() drops stale echoes and refuses an echo
// from the future, telemetry arrives field-for-field, and a board that goes away leaves the
// PC with nothing (not a bogus sample) to take.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "pc/dds/bus.hpp"
#include "pc/dds/domain.hpp"

using namespace std::chrono_literals;
namespace dds = ap::dds;

namespace {

constexpr std::uint32_t kFirstDomain = 100;
constexpr std::uint32_t kLastDomain = 199;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const dds::Error& e) {
    return e.what();
  }
  return "no error";
}

dds::Telemetry sample_telemetry() {
  dds::Telemetry t;
  t.vtime_us = 123'456;
  t.main_state = 2;
  t.ble_status = 3;
  t.led = 4;
  t.charger = true;
  t.usb = true;
  t.low_battery = true;
  t.battery_mv = 3700;
  t.charge_ma = -250;
  t.temperature_mc = 25'500;
  t.rotation_mdeg = 90'000;
  t.axis[0] = dds::AxisTelemetry{1000, 2000, 300, 1, 2, true, false, true, true};
  t.axis[1] = dds::AxisTelemetry{-5, -6, 7, 0, 5, false, true, false, true};
  return t;
}

class dds_bus_edges : public ::testing::Test {
 protected:
  void SetUp() override { dds::use_loopback_config(true); }
};

}  // namespace

TEST_F(dds_bus_edges, DomainLeaseRejectsBadAndExhaustedRanges) {
  EXPECT_EQ(error_of([] { (void)dds::DomainLease::claim(5, 4); }), "dds: bad domain range 5..4");
  EXPECT_EQ(error_of([] { (void)dds::DomainLease::claim(0, dds::kMaxDomainId + 1); }),
            "dds: bad domain range 0..233");
  auto held = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  const std::uint32_t id = held.id();
  EXPECT_EQ(error_of([id] { (void)dds::DomainLease::claim(id, id); }),
            "dds: no free domain id in " + std::to_string(id) + ".." + std::to_string(id));
  // Moving a lease keeps the id held; the moved-from object releases nothing.
  dds::DomainLease moved(std::move(held));
  EXPECT_EQ(moved.id(), id);
  EXPECT_EQ(error_of([id] { (void)dds::DomainLease::claim(id, id); }).rfind("dds: no free domain id", 0), 0U);
}

TEST_F(dds_bus_edges, ImpossibleDomainIsATypedError) {
  const std::string e = error_of([] { dds::Participant p(100000); });
  EXPECT_EQ(e.rfind("dds: create_participant: ", 0), 0U) << e;
}

TEST_F(dds_bus_edges, NoPeerMeansTimeouts) {
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  dds::PcEndpoint pc(lease.id(), 3);
  EXPECT_FALSE(pc.wait_matched(50ms));
  EXPECT_FALSE(pc.take_echo(10ms).has_value());
  EXPECT_FALSE(pc.take_telemetry().has_value());
  const std::vector<std::uint8_t> frame{'a'};
  const std::string e = error_of([&] { (void)pc.step(frame, 1000, 100ms); });
  EXPECT_EQ(e, "dds: board 3 did not answer command 1 (vtime 1000 us) within the timeout");

  dds::BoardEndpoint board(lease.id(), 4);   // another partition: still no peer
  EXPECT_FALSE(board.wait_matched(50ms));
  EXPECT_FALSE(board.take_command(10ms).has_value());
}

// A board that first answers with a stale command number, then the right one: step() skips
// the stale echo. Then a board that answers with a command number from the future: step()
// refuses it.
TEST_F(dds_bus_edges, LockstepSkipsStaleAndRefusesFutureEchoes) {
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  bool board_ok = false;
  std::thread board([&] {
    dds::BoardEndpoint b(lease.id(), 1);
    if (!b.wait_matched(10s)) return;
    const dds::Telemetry t = sample_telemetry();
    auto c1 = b.take_command(10s);
    if (!c1) return;
    dds::CommandSample stale = *c1;
    stale.seq = 0;
    b.echo(stale, std::vector<std::uint8_t>{'s'}, t);
    b.echo(*c1, std::vector<std::uint8_t>{'o', 'k'}, t);
    auto c2 = b.take_command(10s);
    if (!c2) return;
    dds::CommandSample future = *c2;
    future.seq = c2->seq + 5;
    b.echo(future, std::vector<std::uint8_t>{'f'}, t);
    board_ok = true;
    // Stay until the PC is done with the echo (deleting the writer would unregister it).
    (void)b.take_command(5s);
  });
  {
    dds::PcEndpoint pc(lease.id(), 1);
    ASSERT_TRUE(pc.wait_matched(10s));
    const std::vector<std::uint8_t> frame{'c'};
    const dds::EchoSample e = pc.step(frame, 100, 5s);
    EXPECT_EQ(e.cmd_seq, 1U);
    EXPECT_EQ(e.bytes, (std::vector<std::uint8_t>{'o', 'k'}));
    EXPECT_EQ(e.telemetry.axis, sample_telemetry().axis);
    EXPECT_EQ(error_of([&] { (void)pc.step(frame, 200, 5s); }), "dds: echo for command 7 while waiting for 2");
    (void)pc.send(frame, 300, dds::kFlagShutdown);
  }
  board.join();
  EXPECT_TRUE(board_ok);
}

// Telemetry arrives field for field; after the board is gone the PC takes nothing more (the
// writer's unregistration is not a sample).
TEST_F(dds_bus_edges, TelemetryRoundTripAndBoardGone) {
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  dds::PcEndpoint pc(lease.id(), 2);
  const dds::Telemetry sent = sample_telemetry();
  {
    dds::BoardEndpoint b(lease.id(), 2);
    ASSERT_TRUE(b.wait_matched(10s));
    ASSERT_TRUE(pc.wait_matched(10s));
    std::optional<dds::Telemetry> got;
    const auto deadline = std::chrono::steady_clock::now() + 4s;
    while (!got && std::chrono::steady_clock::now() < deadline) {
      b.publish_telemetry(sent);
      std::this_thread::sleep_for(5ms);
      got = pc.take_telemetry();
    }
    ASSERT_TRUE(got.has_value());
    dds::Telemetry expected = sent;
    expected.board = 2;   // stamped by the board endpoint
    EXPECT_TRUE(*got == expected);
    EXPECT_TRUE(got->axis[0] == expected.axis[0]);
    EXPECT_TRUE(got->axis[1] == expected.axis[1]);
    EXPECT_FALSE(got->axis[0] == got->axis[1]);
    // Answer one command, then leave.
    const std::vector<std::uint8_t> frame{'x'};
    (void)pc.send(frame, 10);
    const auto c = b.take_command(5s);
    ASSERT_TRUE(c.has_value());
    b.echo(*c, frame, sent);
    const auto e = pc.take_echo(5s);
    ASSERT_TRUE(e.has_value());
    EXPECT_EQ(e->cmd_seq, c->seq);
  }
  std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(pc.take_echo(50ms).has_value());
  EXPECT_FALSE(pc.take_telemetry().has_value());
}
