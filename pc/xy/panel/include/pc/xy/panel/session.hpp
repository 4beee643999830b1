// The operator's program of seed 000 chapter 8 (docs/panel.md) on the PC side of the DDS bus:
// one delivery client (pc/xy/client) per board, driven in real time, so every button of the
// web panel reaches the board the way the simulated PC's commands do (exactly once, stop
// first, a typed outcome each). The HTTP side (server.hpp) only calls this class; it never
// touches the bus or the client.
//
// Threads: the session's own loop owns the bus endpoints and the clients; the HTTP threads
// hand it requests through a locked queue and read a snapshot it publishes every step.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pc/web/paced_loop.hpp"
#include "pc/web/published.hpp"

namespace ap::xy_panel {

// Something between a board's client and the bus, in each direction: `axisproof panel --faults`
// puts the simulator's fault link here (a link storm under the panel, docs/panel.md). It takes
// the bytes entering at t and returns those leaving at t.
class LinkFilter {
 public:
  virtual ~LinkFilter() = default;
  virtual std::string to_board(std::int64_t t_us, const std::string& bytes) = 0;
  virtual std::string to_pc(std::int64_t t_us, const std::string& bytes) = 0;
};

struct Options {
  std::uint32_t domain = 0;
  std::vector<std::uint32_t> boards{0};  // the board ids to look for on the bus
  std::int64_t period_us = 20'000;        // one command frame per board and period
  // Answers older than this show the unit as out of range (thesis §8.2: the BLE indicator).
  std::int64_t out_of_range_us = 600'000;
  // Makes the link filter of a board; empty: the bytes pass unchanged.
  std::function<std::unique_ptr<LinkFilter>(std::uint32_t board)> link;
};

// What the page asks for. `part`: x, y or unit; `key`: a command key of the codec table
// (protocol/xy/codec/commands.hpp), e.g. goto, move, jog, home, fast, sleep.
struct Request {
  std::uint32_t board = 0;
  std::string part;
  std::string key;
  std::int64_t data = 0;
};

struct Accepted {
  bool ok = false;
  std::string error;    // why it never reached the client (the page shows it)
  std::uint64_t id = 0; // the event id its outcome will carry
};

class Session {
 public:
  explicit Session(Options o);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // A command for the client; refused here (and never sent) when the key, part or data is
  // outside the codec table, the board unknown or not connected.
  Accepted submit(const Request& r);
  // A held arrow key: level -2..2 (0 released) on axis 0 (X) or 1 (Y).
  Accepted hold(std::uint32_t board, int axis, int level);
  // Connect or disconnect the PC from a board (thesis Tab. 8-2's events follow).
  Accepted connect(std::uint32_t board, bool on);
  // The developer extension (thesis §8.3): an environment command to the simulated board
  // (docs/sim.md: usb 0|1, charger 0|1, battery MV, temperature MC, reboot, ...). Blocks until
  // the loop has carried it out; returns the board's reply.
  std::string env(std::uint32_t board, const std::string& line);

  // The developer extension's simulated echo (thesis §8.3): both axes shown with `status` (a
  // key of the codec's status table) and `data` for 3 s, as if the board had sent it.
  Accepted simulate_echo(std::uint32_t board, const std::string& status, std::int32_t data);

  // The latest state and every event with an id above `after`.
  nlohmann::json snapshot(std::uint64_t after) const;
  // The tables the page validates with (commands and statuses with their ranges and words).
  static nlohmann::json tables();

  void stop();

 private:
  struct Board;
  struct Pending;
  void step(std::int64_t t);
  void event(nlohmann::json e) { pub_.event(std::move(e)); }
  // Hands a request to the loop (it takes it within one period) and waits for its answer; after
  // stop() the answer is at once that the panel is shutting down.
  Accepted queue(std::unique_ptr<Pending> p);
  void push(std::unique_ptr<Pending> p);
  static void answer_shut_down(Pending& p);

  Options opt_;
  std::vector<std::unique_ptr<Board>> boards_;
  std::mutex mu_;  // pending_, stopped_
  std::deque<std::unique_ptr<Pending>> pending_;
  bool stopped_ = false;
  web::Published pub_;
  std::unique_ptr<web::PacedLoop> loop_;  // last: it runs step() on the members above
};

}  // namespace ap::xy_panel
