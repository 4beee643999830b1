// ap::dds: the DDS test bus between a simulated PC and simulated boards (docs/dds.md).
//
// PC-side code (exceptions and the heap are fine). Wraps the Cyclone DDS C API in RAII types:
//   Participant    one DDS participant on a domain (shared by several endpoints in one process)
//   PcEndpoint     the PC end of one board's link: send command frames, take echoes, lockstep step()
//   BoardEndpoint  the board end: take commands, answer each with one echo, publish telemetry
//   DomainLease    (domain.hpp) claims a free domain id so parallel tests never share one
//
// Lockstep: every Command carries the virtual time the board must run up to before it applies
// the frame; the board answers every Command with exactly one Echo (frame bytes possibly empty)
// carrying its state at that time. PcEndpoint::step() = send + wait for that echo.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace ap::dds {

inline constexpr std::size_t kFrameMax = 128;   // ap_bus::FRAME_MAX in idl/ApBus.idl
inline constexpr std::uint32_t kFlagShutdown = 1;
inline constexpr std::uint32_t kFlagRealtime = 2;
// A harness ("environment") command: the bytes are a text line for the board's env(), the
// echo's bytes its text reply; the board's clock does not move (docs/sim.md).
inline constexpr std::uint32_t kFlagEnv = 0x100;

// Topic names (docs/dds.md has the QoS of each).
inline constexpr const char* kCommandTopic = "ap_command";
inline constexpr const char* kEchoTopic = "ap_echo";
inline constexpr const char* kTelemetryTopic = "ap_telemetry";

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct AxisTelemetry {
  std::int32_t pos = 0;
  std::int32_t target = 0;
  std::int32_t speed = 0;
  std::uint8_t dir = 0;
  std::uint8_t state = 0;
  bool endstop_min = false;
  bool endstop_max = false;
  bool blocked = false;
  bool enabled = false;
  friend bool operator==(const AxisTelemetry&, const AxisTelemetry&) = default;
};

struct Telemetry {
  std::uint32_t board = 0;
  std::uint64_t vtime_us = 0;
  std::uint8_t main_state = 0;
  std::uint8_t ble_status = 0;
  std::uint8_t led = 0;
  bool charger = false;
  bool usb = false;
  bool low_battery = false;
  std::uint16_t battery_mv = 0;
  std::int16_t charge_ma = 0;
  std::int32_t temperature_mc = 0;
  std::int32_t rotation_mdeg = 0;
  std::array<AxisTelemetry, 2> axis{};
  friend bool operator==(const Telemetry&, const Telemetry&) = default;
};

struct CommandSample {
  std::uint32_t board = 0;
  std::uint64_t seq = 0;
  std::uint64_t vtime_us = 0;
  std::int64_t wall_ns = 0;
  std::uint32_t flags = 0;
  std::vector<std::uint8_t> bytes;
};

struct EchoSample {
  std::uint32_t board = 0;
  std::uint64_t seq = 0;
  std::uint64_t cmd_seq = 0;
  std::uint64_t vtime_us = 0;
  std::int64_t wall_ns = 0;
  std::int64_t cmd_wall_ns = 0;
  std::vector<std::uint8_t> bytes;
  Telemetry telemetry;
};

// CLOCK_MONOTONIC in ns (the wall_ns fields).
std::int64_t now_ns();

// The loopback-only configuration (pc/dds/config/loopback.xml) as Cyclone's inline XML, a
// value for CYCLONEDDS_URI that needs no file.
std::string loopback_config_uri();
// Sets CYCLONEDDS_URI to loopback_config_uri() unless it is already set (overwrite = false).
// Must run before the first participant of a domain is created in this process.
void use_loopback_config(bool overwrite = false);

class Participant {
 public:
  explicit Participant(std::uint32_t domain);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;
  [[nodiscard]] std::int32_t handle() const { return pp_; }
  [[nodiscard]] std::uint32_t domain() const { return domain_; }

 private:
  std::int32_t pp_;
  std::uint32_t domain_;
};

using ParticipantPtr = std::shared_ptr<Participant>;
ParticipantPtr make_participant(std::uint32_t domain);

namespace detail {
// The setup both ends share (docs/dds.md): the board's partition, a publisher and a
// subscriber in it, the reliable writer of what this end sends, the reliable reader of what
// the other end sends (the waitset wakes on it), and the best-effort telemetry topic, which
// the board writes and the PC reads. The two ends differ only in which topic is which.
class Endpoint {
 public:
  Endpoint(const Endpoint&) = delete;
  Endpoint& operator=(const Endpoint&) = delete;
  // True once this end's writer and reader both match the other end.
  bool wait_matched(std::chrono::milliseconds timeout);
  [[nodiscard]] std::uint32_t board() const { return board_; }

 protected:
  enum class Side : std::uint8_t { pc, board };
  Endpoint(ParticipantPtr participant, std::uint32_t board, Side side);
  ~Endpoint();

  ParticipantPtr pp_;
  std::uint32_t board_;
  std::uint64_t next_seq_ = 1;
  std::int32_t pub_ = 0, sub_ = 0, wr_ = 0, rd_ = 0, tel_ = 0, ws_ = 0, cond_ = 0;
};
}  // namespace detail

class PcEndpoint : public detail::Endpoint {
 public:
  PcEndpoint(ParticipantPtr participant, std::uint32_t board);
  PcEndpoint(std::uint32_t domain, std::uint32_t board);  // with a participant of its own

  // Publishes one Command (reliable); returns its bus sequence number.
  std::uint64_t send(std::span<const std::uint8_t> frame, std::uint64_t vtime_us, std::uint32_t flags = 0);
  // Next echo in order, or nothing after timeout.
  std::optional<EchoSample> take_echo(std::chrono::milliseconds timeout);
  // Lockstep: send, then wait for the echo answering exactly that command (older echoes are
  // dropped). Throws Error on timeout or on an echo from the future.
  EchoSample step(std::span<const std::uint8_t> frame, std::uint64_t vtime_us,
                  std::chrono::milliseconds timeout = std::chrono::seconds(5));
  // Latest best-effort telemetry sample, if any arrived since the last call.
  std::optional<Telemetry> take_telemetry();
};

class BoardEndpoint : public detail::Endpoint {
 public:
  BoardEndpoint(ParticipantPtr participant, std::uint32_t board);
  BoardEndpoint(std::uint32_t domain, std::uint32_t board);

  std::optional<CommandSample> take_command(std::chrono::milliseconds timeout);
  // Answers `cmd` (exactly once per command in lockstep). `frame` may be empty.
  void echo(const CommandSample& cmd, std::span<const std::uint8_t> frame, const Telemetry& state);
  void publish_telemetry(const Telemetry& state);
};

}  // namespace ap::dds
