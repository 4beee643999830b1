// Seed 001's PC program (seed-001.md §7) behind the web panel (docs/panel.md "The unit3
// panel"): one unit on the DDS bus, its `;` lines sent as the program sends them (`M…;`, `T…;`
// when the settings changed, `D…;`, then `X…;`/`Y…;`/`Z…;`; `C;` on "0 0 0"), and what the unit
// answers (its counter reports, its settings, its `E…;` refusals) read back for the page. Its
// own loop owns the bus; the HTTP threads queue requests and read the published snapshot.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pc/unit3/panel/conversion.hpp"
#include "protocol/unit3/wire/dialect.hpp"
#include "pc/web/paced_loop.hpp"
#include "pc/web/published.hpp"

namespace ap::unit3_panel {

struct Options {
  std::uint32_t domain = 0;
  std::uint32_t board = 0;
  std::int64_t period_us = 10'000;
};

// What Send carries per axis: the displacement in µm, the step mode and the thread chosen.
struct SendRequest {
  std::array<std::int64_t, 3> um{};
  std::array<std::uint8_t, 3> mode{};
  std::array<std::uint8_t, 3> thread{};
};

struct Sent {
  bool ok = false;
  std::string error;
  std::vector<std::string> lines;            // what went to the unit
  std::array<Conversion, 3> conversions{};
};

class Session {
 public:
  explicit Session(Options o);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Send: each axis converted (conversion.hpp), refused whole if one axis cannot be.
  Sent send(const SendRequest& r);
  // "0 0 0": `C;`, and the program's counters and positions go to 0.
  Sent clear();
  // `G;`: the unit answers with its step modes and threads (`M…;T…;`), which the page's
  // selection boxes take (seed-001.md §7 [I]).
  Sent get_settings();
  nlohmann::json snapshot(std::uint64_t after) const;
  static nlohmann::json tables();
  void stop();

 private:
  void step(std::int64_t t);
  void event(nlohmann::json e) { pub_.event(std::move(e)); }
  void read(const std::string& line);
  // The lines go to the unit with the loop's next step; the caller holds mu_.
  void queue_locked(const std::vector<std::string>& lines, bool clear);
  // A command without fields (`C;`, `G;`) in the wire's own format, queued.
  Sent send_one(unit3_wire::Kind kind);

  struct Pending {
    std::vector<std::string> lines;
    bool clear = false;
  };
  struct Impl;

  Options opt_;
  std::unique_ptr<Impl> impl_;
  std::mutex mu_;  // pending_, sent_mode_, sent_thread_ and the thread the positions are shown in
  std::deque<std::unique_ptr<Pending>> pending_;
  // What the program last sent (the settings lines go only when they change).
  std::array<int, 3> sent_mode_{-1, -1, -1};
  std::array<int, 3> sent_thread_{-1, -1, -1};
  web::Published pub_;
  std::unique_ptr<web::PacedLoop> loop_;  // last: it runs step() on the members above
};

}  // namespace ap::unit3_panel
