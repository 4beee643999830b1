// What a panel's session publishes for its page (docs/panel.md "HTTP"), the same for every
// profile: the latest state and the events, each with an id (the last 500 kept), so the events
// stream can send each tab what it has not seen. One lock of its own, taken by the session's
// loop to publish and by the HTTP threads to read.
#pragma once

#include <cstdint>
#include <deque>
#include <mutex>

#include <nlohmann/json.hpp>

namespace ap::web {

class Published {
 public:
  void event(nlohmann::json e);
  void state(nlohmann::json s);
  // The state with "events": every event with an id above `after`.
  [[nodiscard]] nlohmann::json snapshot(std::uint64_t after) const;

 private:
  mutable std::mutex mu_;
  nlohmann::json state_ = nlohmann::json::object();
  std::deque<nlohmann::json> events_;
  std::uint64_t next_ = 1;
};

}  // namespace ap::web
