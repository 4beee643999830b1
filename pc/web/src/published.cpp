// A session's published state and events (published.hpp).
#include "pc/web/published.hpp"

#include <utility>

namespace ap::web {

void Published::event(nlohmann::json e) {
  std::lock_guard<std::mutex> l(mu_);
  e["id"] = next_++;
  events_.push_back(std::move(e));
  while (events_.size() > 500) events_.pop_front();
}

void Published::state(nlohmann::json s) {
  std::lock_guard<std::mutex> l(mu_);
  state_ = std::move(s);
}

nlohmann::json Published::snapshot(std::uint64_t after) const {
  std::lock_guard<std::mutex> l(mu_);
  nlohmann::json s = state_;
  s["events"] = nlohmann::json::array();
  for (const auto& e : events_) {
    if (e["id"].get<std::uint64_t>() > after) s["events"].push_back(e);
  }
  return s;
}

}  // namespace ap::web
