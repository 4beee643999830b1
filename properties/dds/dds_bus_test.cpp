// End-to-end checks of the DDS test bus: two participants (threads, and a forked process) on a
// private domain exchange raw frames; delivery, order, lockstep and the loopback-only config.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
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

std::vector<std::uint8_t> frame_for(std::uint64_t i, std::size_t len) {
  std::vector<std::uint8_t> f(len);
  for (std::size_t k = 0; k < len; ++k) {
    f[k] = static_cast<std::uint8_t>('0' + (i + k) % 10);
  }
  return f;
}

// The board side of the tests: answers each command with an echo that reverses the frame and
// advances its virtual clock to the command's vtime; stops on the shutdown flag.
int run_board(std::uint32_t domain, std::uint32_t board, std::chrono::milliseconds idle_timeout) {
  dds::BoardEndpoint b(domain, board);
  if (!b.wait_matched(10s)) {
    return 2;
  }
  std::uint64_t last_seq = 0;
  for (;;) {
    auto c = b.take_command(idle_timeout);
    if (!c) {
      return 3;
    }
    if (c->seq != last_seq + 1) {
      return 4;  // out of order or a gap
    }
    last_seq = c->seq;
    dds::Telemetry t;
    t.vtime_us = c->vtime_us;
    t.axis[0].pos = static_cast<std::int32_t>(c->seq);
    t.axis[1].pos = -static_cast<std::int32_t>(c->seq);
    t.ble_status = 2;
    std::vector<std::uint8_t> reply(c->bytes.rbegin(), c->bytes.rend());
    b.echo(*c, reply, t);
    b.publish_telemetry(t);
    if ((c->flags & dds::kFlagShutdown) != 0U) {
      return 0;
    }
  }
}

class dds_bus : public ::testing::Test {
 protected:
  void SetUp() override { dds::use_loopback_config(true); }
};

}  // namespace

TEST_F(dds_bus, DomainLeasesAreExclusive) {
  auto a = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  auto b = dds::DomainLease::claim(a.id(), kLastDomain);
  EXPECT_NE(a.id(), b.id());
  EXPECT_GT(b.id(), a.id());
}

TEST_F(dds_bus, LockstepTwoThreadsDeliversInOrder) {
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  int board_rc = -1;
  std::thread board([&] { board_rc = run_board(lease.id(), 7, 10s); });
  {
    dds::PcEndpoint pc(lease.id(), 7);
    ASSERT_TRUE(pc.wait_matched(10s));
    constexpr std::uint64_t kSteps = 200;
    for (std::uint64_t i = 1; i <= kSteps; ++i) {
      const auto f = frame_for(i, 1 + i % dds::kFrameMax);
      const std::uint64_t vtime = i * 100'000;  // one command per 100 ms of virtual time
      const dds::EchoSample e =
          i == kSteps ? (pc.send(f, vtime, dds::kFlagShutdown), *pc.take_echo(10s)) : pc.step(f, vtime);
      ASSERT_EQ(e.cmd_seq, i);
      ASSERT_EQ(e.seq, i);
      ASSERT_EQ(e.board, 7U);
      ASSERT_EQ(e.vtime_us, vtime);
      ASSERT_EQ(e.telemetry.axis[0].pos, static_cast<std::int32_t>(i));
      ASSERT_EQ(e.telemetry.axis[1].pos, -static_cast<std::int32_t>(i));
      ASSERT_EQ(e.bytes, std::vector<std::uint8_t>(f.rbegin(), f.rend()));
      ASSERT_GE(e.wall_ns, e.cmd_wall_ns);
    }
  }
  board.join();
  EXPECT_EQ(board_rc, 0);
}

TEST_F(dds_bus, PipelinedBurstArrivesCompleteAndOrdered) {
  // Not lockstep: 60 commands written back to back (below the history depth of 64).
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  int board_rc = -1;
  std::thread board([&] { board_rc = run_board(lease.id(), 1, 10s); });
  {
    dds::PcEndpoint pc(lease.id(), 1);
    ASSERT_TRUE(pc.wait_matched(10s));
    constexpr std::uint64_t kN = 60;
    for (std::uint64_t i = 1; i <= kN; ++i) {
      pc.send(frame_for(i, 16), i, i == kN ? dds::kFlagShutdown : 0U);
    }
    for (std::uint64_t i = 1; i <= kN; ++i) {
      auto e = pc.take_echo(10s);
      ASSERT_TRUE(e.has_value()) << "echo " << i << " missing";
      ASSERT_EQ(e->cmd_seq, i);
    }
  }
  board.join();
  EXPECT_EQ(board_rc, 0);
}

TEST_F(dds_bus, BoardsAreIsolatedByPartition) {
  // Two boards share one participant per side (as 32 boards in one process would); each PC
  // endpoint sees only its own board's echoes.
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  auto board_pp = dds::make_participant(lease.id());
  auto pc_pp = dds::make_participant(lease.id());
  dds::BoardEndpoint b0(board_pp, 0);
  dds::BoardEndpoint b1(board_pp, 1);
  dds::PcEndpoint p0(pc_pp, 0);
  dds::PcEndpoint p1(pc_pp, 1);
  ASSERT_TRUE(p0.wait_matched(10s) && p1.wait_matched(10s) && b0.wait_matched(10s) && b1.wait_matched(10s));
  const std::vector<std::uint8_t> f0{'A'};
  const std::vector<std::uint8_t> f1{'B'};
  p0.send(f0, 100);
  p1.send(f1, 100);
  auto c0 = b0.take_command(5s);
  auto c1 = b1.take_command(5s);
  ASSERT_TRUE(c0 && c1);
  EXPECT_EQ(c0->bytes, f0);
  EXPECT_EQ(c1->bytes, f1);
  EXPECT_FALSE(b0.take_command(50ms).has_value());
  dds::Telemetry t;
  t.vtime_us = 100;
  b0.echo(*c0, c0->bytes, t);
  b1.echo(*c1, c1->bytes, t);
  auto e0 = p0.take_echo(5s);
  auto e1 = p1.take_echo(5s);
  ASSERT_TRUE(e0 && e1);
  EXPECT_EQ(e0->telemetry.board, 0U);
  EXPECT_EQ(e1->telemetry.board, 1U);
  EXPECT_EQ(e1->bytes, f1);
  EXPECT_FALSE(p0.take_echo(50ms).has_value());
}

TEST_F(dds_bus, TwoProcessesRoundTrip) {
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  const pid_t child = fork();  // before any DDS thread of this process exists
  ASSERT_GE(child, 0);
  if (child == 0) {
    _exit(run_board(lease.id(), 3, 10s));
  }
  {
    dds::PcEndpoint pc(lease.id(), 3);
    ASSERT_TRUE(pc.wait_matched(15s));
    for (std::uint64_t i = 1; i <= 50; ++i) {
      const auto f = frame_for(i, 40);
      const std::uint32_t flags = i == 50 ? dds::kFlagShutdown : 0U;
      pc.send(f, i * 1000, flags);
      auto e = pc.take_echo(10s);
      ASSERT_TRUE(e.has_value());
      ASSERT_EQ(e->cmd_seq, i);
      ASSERT_EQ(e->bytes, std::vector<std::uint8_t>(f.rbegin(), f.rend()));
    }
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST_F(dds_bus, OversizedFrameIsRejected) {
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  dds::PcEndpoint pc(lease.id(), 0);
  const std::vector<std::uint8_t> big(dds::kFrameMax + 1, 'x');
  EXPECT_THROW(pc.send(big, 0), dds::Error);
}

TEST_F(dds_bus, LoopbackOnlyConfigIsApplied) {
  // Cyclone traces its effective configuration and the interface it selected; the test adds a
  // tracing fragment to the shipped file and reads the trace back.
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  const std::filesystem::path trace =
      std::filesystem::temp_directory_path() / ("ap-dds-trace-" + std::to_string(getpid()) + ".log");
  const std::string uri = dds::loopback_config_uri() + ",<Tracing><Category>config</Category><OutputFile>" +
                          trace.string() + "</OutputFile></Tracing>";
  setenv("CYCLONEDDS_URI", uri.c_str(), 1);
  {
    dds::BoardEndpoint b(lease.id(), 0);
    dds::PcEndpoint pc(lease.id(), 0);
    ASSERT_TRUE(pc.wait_matched(10s));
  }
  std::ifstream in(trace);
  ASSERT_TRUE(in.good()) << trace;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string log = ss.str();
  std::filesystem::remove(trace);
  EXPECT_NE(log.find("selected interfaces: lo "), std::string::npos) << log.substr(0, 2000);
  EXPECT_NE(log.find("General/AllowMulticast/#text: false"), std::string::npos);
  EXPECT_NE(log.find("Discovery/ParticipantIndex/#text: auto"), std::string::npos);
  EXPECT_NE(log.find("Peers/Peer[@Address]: 127.0.0.1"), std::string::npos);
  EXPECT_EQ(log.find("selected interfaces: eth"), std::string::npos);
}
