// ap::dds wrapper over the Cyclone DDS C API (docs/dds.md).
#include "pc/dds/bus.hpp"

#include <dds/dds.h>

#include <cstdlib>
#include <ctime>
#include <string>
#include <thread>

#include "ApBus.h"
#include "loopback_config.hpp"

namespace ap::dds {
namespace {

// History depth of the reliable topics. Lockstep keeps one sample in flight; realtime mode
// sends 10 per second; 64 lets a board that stalls for seconds catch up without loss.
constexpr std::int32_t kReliableDepth = 64;

dds_entity_t check(dds_entity_t e, const char* what) {
  if (e < 0) {
    throw Error(std::string("dds: ") + what + ": " + dds_strretcode(e));
  }
  return e;
}

void check_rc(dds_return_t rc, const char* what) {
  if (rc < 0) {
    throw Error(std::string("dds: ") + what + ": " + dds_strretcode(rc));
  }
}

std::string partition_of(std::uint32_t board) { return "ap.board." + std::to_string(board); }

struct QosDeleter {
  void operator()(dds_qos_t* q) const { dds_delete_qos(q); }
};
using QosPtr = std::unique_ptr<dds_qos_t, QosDeleter>;

QosPtr reliable_qos() {
  QosPtr q(dds_create_qos());
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, kReliableDepth);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  dds_qset_destination_order(q.get(), DDS_DESTINATIONORDER_BY_SOURCE_TIMESTAMP);
  return q;
}

QosPtr best_effort_qos() {
  QosPtr q(dds_create_qos());
  dds_qset_reliability(q.get(), DDS_RELIABILITY_BEST_EFFORT, 0);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  return q;
}

QosPtr partition_qos(std::uint32_t board) {
  QosPtr q(dds_create_qos());
  const std::string p = partition_of(board);
  dds_qset_partition1(q.get(), p.c_str());
  return q;
}

dds_entity_t topic(dds_entity_t pp, const dds_topic_descriptor_t* desc, const char* name) {
  return check(dds_create_topic(pp, desc, name, nullptr, nullptr), "create_topic");
}

dds_sequence_octet as_sequence(std::span<const std::uint8_t> frame) {
  if (frame.size() > kFrameMax) {
    throw Error("dds: frame of " + std::to_string(frame.size()) + " bytes exceeds FRAME_MAX");
  }
  dds_sequence_octet s{};
  s._maximum = static_cast<std::uint32_t>(frame.size());
  s._length = static_cast<std::uint32_t>(frame.size());
  // Cyclone only reads the buffer during dds_write; _release = false: not ours to free.
  s._buffer = const_cast<std::uint8_t*>(frame.data());
  s._release = false;
  return s;
}

std::vector<std::uint8_t> from_sequence(const dds_sequence_octet& s) {
  return {s._buffer, s._buffer + s._length};
}

ap_bus_Telemetry to_idl(const Telemetry& t) {
  ap_bus_Telemetry o{};
  o.board = t.board;
  o.vtime_us = t.vtime_us;
  o.main_state = t.main_state;
  o.ble_status = t.ble_status;
  o.led = t.led;
  o.charger = t.charger;
  o.usb = t.usb;
  o.low_battery = t.low_battery;
  o.battery_mv = t.battery_mv;
  o.charge_ma = t.charge_ma;
  o.temperature_mc = t.temperature_mc;
  o.rotation_mdeg = t.rotation_mdeg;
  for (std::size_t i = 0; i < 2; ++i) {
    const AxisTelemetry& a = t.axis[i];
    o.axis[i] = ap_bus_AxisTelemetry{a.pos, a.target, a.speed, a.dir, a.state,
                                     a.endstop_min, a.endstop_max, a.blocked, a.enabled};
  }
  return o;
}

Telemetry from_idl(const ap_bus_Telemetry& o) {
  Telemetry t;
  t.board = o.board;
  t.vtime_us = o.vtime_us;
  t.main_state = o.main_state;
  t.ble_status = o.ble_status;
  t.led = o.led;
  t.charger = o.charger;
  t.usb = o.usb;
  t.low_battery = o.low_battery;
  t.battery_mv = o.battery_mv;
  t.charge_ma = o.charge_ma;
  t.temperature_mc = o.temperature_mc;
  t.rotation_mdeg = o.rotation_mdeg;
  for (std::size_t i = 0; i < 2; ++i) {
    const ap_bus_AxisTelemetry& a = o.axis[i];
    t.axis[i] = AxisTelemetry{a.pos, a.target, a.speed, a.dir, a.state,
                              a.endstop_min, a.endstop_max, a.blocked, a.enabled};
  }
  return t;
}

// Takes one valid sample from `rd`, waiting on `ws` up to `timeout`; `copy` converts it.
template <typename Sample, typename Copy>
auto take_one(dds_entity_t rd, dds_entity_t ws, std::chrono::milliseconds timeout, Copy copy)
    -> std::optional<decltype(copy(std::declval<const Sample&>()))> {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    const dds_return_t n = dds_take(rd, samples, &info, 1, 1);
    check_rc(n, "take");
    if (n > 0) {
      std::optional<decltype(copy(std::declval<const Sample&>()))> out;
      if (info.valid_data) {
        out = copy(*static_cast<const Sample*>(samples[0]));
      }
      check_rc(dds_return_loan(rd, samples, n), "return_loan");
      if (out) {
        return out;
      }
      continue;  // an instance-state change without data: look again
    }
    const auto left = deadline - std::chrono::steady_clock::now();
    if (left <= std::chrono::steady_clock::duration::zero()) {
      return std::nullopt;
    }
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
    check_rc(dds_waitset_wait(ws, nullptr, 0, static_cast<dds_duration_t>(ns)), "waitset_wait");
  }
}

bool matched(dds_entity_t wr, dds_entity_t rd) {
  dds_publication_matched_status_t ps{};
  dds_subscription_matched_status_t ss{};
  check_rc(dds_get_publication_matched_status(wr, &ps), "publication_matched_status");
  check_rc(dds_get_subscription_matched_status(rd, &ss), "subscription_matched_status");
  return ps.current_count > 0 && ss.current_count > 0;
}

bool wait_until_matched(dds_entity_t wr, dds_entity_t rd, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!matched(wr, rd)) {
    if (std::chrono::steady_clock::now() >= deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::string loopback_config_uri() { return kLoopbackConfig; }

void use_loopback_config(bool overwrite) {
  const std::string uri = loopback_config_uri();
  setenv("CYCLONEDDS_URI", uri.c_str(), overwrite ? 1 : 0);
}

Participant::Participant(std::uint32_t domain)
    : pp_(check(dds_create_participant(domain, nullptr, nullptr), "create_participant")),
      domain_(domain) {}

Participant::~Participant() { dds_delete(pp_); }

ParticipantPtr make_participant(std::uint32_t domain) { return std::make_shared<Participant>(domain); }

// ------------------------------------------------------------------------------ both ends

namespace detail {

Endpoint::Endpoint(ParticipantPtr participant, std::uint32_t board, Side side)
    : pp_(std::move(participant)), board_(board) {
  const dds_entity_t pp = pp_->handle();
  const QosPtr part = partition_qos(board);
  pub_ = check(dds_create_publisher(pp, part.get(), nullptr), "create_publisher");
  sub_ = check(dds_create_subscriber(pp, part.get(), nullptr), "create_subscriber");
  try {
    const QosPtr rel = reliable_qos();
    const QosPtr be = best_effort_qos();
    const dds_entity_t command = topic(pp, &ap_bus_Command_desc, kCommandTopic);
    const dds_entity_t echo = topic(pp, &ap_bus_Echo_desc, kEchoTopic);
    const dds_entity_t telemetry = topic(pp, &ap_bus_Telemetry_desc, kTelemetryTopic);
    const bool pc = side == Side::pc;
    wr_ = check(dds_create_writer(pub_, pc ? command : echo, rel.get(), nullptr), "create_writer");
    rd_ = check(dds_create_reader(sub_, pc ? echo : command, rel.get(), nullptr), "create_reader");
    tel_ = pc ? check(dds_create_reader(sub_, telemetry, be.get(), nullptr), "create_reader telemetry")
              : check(dds_create_writer(pub_, telemetry, be.get(), nullptr), "create_writer telemetry");
    ws_ = check(dds_create_waitset(pp), "create_waitset");
    cond_ = check(dds_create_readcondition(rd_, DDS_ANY_STATE), "create_readcondition");
    check_rc(dds_waitset_attach(ws_, cond_, rd_), "waitset_attach");
  } catch (...) {
    dds_delete(pub_);
    dds_delete(sub_);
    throw;
  }
}

Endpoint::~Endpoint() {
  // Topics stay with the participant (shared by other endpoints); it deletes them last.
  dds_delete(ws_);
  dds_delete(pub_);
  dds_delete(sub_);
}

bool Endpoint::wait_matched(std::chrono::milliseconds timeout) { return wait_until_matched(wr_, rd_, timeout); }

}  // namespace detail

// ---------------------------------------------------------------------------------------- PC

PcEndpoint::PcEndpoint(std::uint32_t domain, std::uint32_t board)
    : PcEndpoint(make_participant(domain), board) {}

PcEndpoint::PcEndpoint(ParticipantPtr participant, std::uint32_t board)
    : Endpoint(std::move(participant), board, Side::pc) {}

std::uint64_t PcEndpoint::send(std::span<const std::uint8_t> frame, std::uint64_t vtime_us, std::uint32_t flags) {
  ap_bus_Command c{};
  c.board = board_;
  c.seq = next_seq_++;
  c.vtime_us = vtime_us;
  c.flags = flags;
  c.bytes = as_sequence(frame);
  c.wall_ns = now_ns();
  check_rc(dds_write(wr_, &c), "write command");
  return c.seq;
}

std::optional<EchoSample> PcEndpoint::take_echo(std::chrono::milliseconds timeout) {
  return take_one<ap_bus_Echo>(rd_, ws_, timeout, [](const ap_bus_Echo& e) {
    EchoSample s;
    s.board = e.board;
    s.seq = e.seq;
    s.cmd_seq = e.cmd_seq;
    s.vtime_us = e.vtime_us;
    s.wall_ns = e.wall_ns;
    s.cmd_wall_ns = e.cmd_wall_ns;
    s.bytes = from_sequence(e.bytes);
    s.telemetry = from_idl(e.telemetry);
    return s;
  });
}

EchoSample PcEndpoint::step(std::span<const std::uint8_t> frame, std::uint64_t vtime_us,
                            std::chrono::milliseconds timeout) {
  const std::uint64_t seq = send(frame, vtime_us);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    std::optional<EchoSample> e = take_echo(std::max(left, std::chrono::milliseconds(0)));
    if (!e) {
      throw Error("dds: board " + std::to_string(board_) + " did not answer command " + std::to_string(seq) +
                  " (vtime " + std::to_string(vtime_us) + " us) within the timeout");
    }
    if (e->cmd_seq == seq) {
      return std::move(*e);
    }
    if (e->cmd_seq > seq) {
      throw Error("dds: echo for command " + std::to_string(e->cmd_seq) + " while waiting for " + std::to_string(seq));
    }
  }
}

std::optional<Telemetry> PcEndpoint::take_telemetry() {
  std::optional<Telemetry> last;
  for (;;) {
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    const dds_return_t n = dds_take(tel_, samples, &info, 1, 1);
    check_rc(n, "take telemetry");
    if (n == 0) {
      return last;
    }
    if (info.valid_data) {
      last = from_idl(*static_cast<const ap_bus_Telemetry*>(samples[0]));
    }
    check_rc(dds_return_loan(tel_, samples, n), "return_loan");
  }
}

// ------------------------------------------------------------------------------------- board

BoardEndpoint::BoardEndpoint(std::uint32_t domain, std::uint32_t board)
    : BoardEndpoint(make_participant(domain), board) {}

BoardEndpoint::BoardEndpoint(ParticipantPtr participant, std::uint32_t board)
    : Endpoint(std::move(participant), board, Side::board) {}

std::optional<CommandSample> BoardEndpoint::take_command(std::chrono::milliseconds timeout) {
  return take_one<ap_bus_Command>(rd_, ws_, timeout, [](const ap_bus_Command& c) {
    CommandSample s;
    s.board = c.board;
    s.seq = c.seq;
    s.vtime_us = c.vtime_us;
    s.wall_ns = c.wall_ns;
    s.flags = c.flags;
    s.bytes = from_sequence(c.bytes);
    return s;
  });
}

void BoardEndpoint::echo(const CommandSample& cmd, std::span<const std::uint8_t> frame, const Telemetry& state) {
  ap_bus_Echo e{};
  e.board = board_;
  e.seq = next_seq_++;
  e.cmd_seq = cmd.seq;
  e.vtime_us = state.vtime_us;
  e.cmd_wall_ns = cmd.wall_ns;
  e.bytes = as_sequence(frame);
  e.telemetry = to_idl(state);
  e.telemetry.board = board_;
  e.wall_ns = now_ns();
  check_rc(dds_write(wr_, &e), "write echo");
}

void BoardEndpoint::publish_telemetry(const Telemetry& state) {
  ap_bus_Telemetry t = to_idl(state);
  t.board = board_;
  check_rc(dds_write(tel_, &t), "write telemetry");
}

}  // namespace ap::dds
