// Wires the echo model (echo_model.hpp) to a running xy_board::Board: a twin of the receive path
// turns the UART bytes into frame events, the board's sampled inputs and axis motion feed the
// model, and every echo the board sent in the tick is compared with its prediction.
//
// Used by the stateful property test (properties/xy/board), the simulated board (sim/)
// and, later, the board fuzz target. Per tick:
//   checker.rx(bytes);                     // whatever was handed to board.uart_rx()
//   board.tick();
//   for (auto& m : checker.after_tick(echo_bytes_sent_in_that_tick, sensors_of(...))) report(m);
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/board/board.hpp"
#include "core/xy/frame/stream_framer.hpp"
#include "core/xy/storage/parameters.hpp"
#include "models/xy/fram/mb85rs256b.hpp"
#include "models/xy/echo/echo_model.hpp"
#include "models/xy/icm20789/device.hpp"
#include "models/xy/tmp117/device.hpp"

namespace ap::model::xy_echo {

using EchoBytes = std::array<std::uint8_t, xy_codec::kEchoLength>;

// The link layer as docs/board.md "One cycle" step 3 describes it: bytes stored by the
// receive interrupt wait in a ring and are framed at the next tick; how many frame events a
// tick takes is the model's business (at most four answered, at most one new frame taken), so
// the twin hands them out one at a time and the rest wait. The framer itself is core/xy/frame's
// (verified by properties/xy/protocol); what a frame means is the model's business.
class LinkTwin {
 public:
  void rx(std::span<const std::uint8_t> bytes);
  // The next frame event in the ring (its bytes consumed), or nullopt when the ring holds no
  // complete one (the bytes read so far stay in the framer).
  std::optional<FrameEvent> next();

 private:
  std::vector<std::uint8_t> ring_;
  xy_frame::RawCommandFramer framer_;
};

// Boot facts of a board, as a test that set up its inputs knows them: an axis is homed when
// its encoder reading was valid at boot (docs/board.md "Step counter and boot"; a saved
// counter is the other way, which the caller states).
// The step counters are read from the booted board (an observation, like all positions).
Boot boot_facts(const xy_board::Board& b, const xy_board::Inputs& at_boot, std::array<bool, kAxes> saved_counter_valid = {});

// What a boot from this chip loads (docs/storage.md: the newest valid copy), read by a store
// of its own over a copy of the chip; the storage tests verify the store itself.
xy_storage::ParameterSet stored_set(model::Mb85rs256b chip);

// Boot facts with the parameter set the boot loaded (its saved step counters included).
Boot boot_facts(const xy_board::Board& b, const xy_board::Inputs& at_boot, const xy_storage::ParameterSet& stored);

// Env and Motion from the board's observers (the sampled inputs; the axis core's phase and
// step counter and this tick's motor output; the path's active flag and queue length).
// The sensors are not among them: sensors_of() below.
Env env_of(const xy_board::Inputs& in);

// The I2C sensors as their device models hold them (registers read as oracles, not over the
// bus), with how every transaction to each ends now (Ok, or the failure the bus or a missing
// part gives; NoPort: the board has no sensor bus).
Sensors sensors_of(const model::xy_tmp117::Device& t, ap::xy_i2c::Status t_answers, const model::xy_icm20789::Device& g,
                   ap::xy_i2c::Status g_answers);
Motion motion_of(const xy_board::Board& b);

class BoardChecker {
 public:
  BoardChecker(const xy_board::Board& b, const Boot& boot) : board_(b), model_(boot) {}
  void rx(std::span<const std::uint8_t> bytes) { link_.rx(bytes); }
  // After board.tick(): the echoes the board sent during that tick and the sensors as they
  // stood during it (default: no sensor bus). Returns the disagreements (empty when the board
  // agrees with the model), each one readable.
  std::vector<std::string> after_tick(std::span<const EchoBytes> sent, const Sensors& sensors = {});
  EchoModel& model() { return model_; }

 private:
  const xy_board::Board& board_;
  EchoModel model_;
  LinkTwin link_;
};

}  // namespace ap::model::xy_echo
