// A panel session's loop (docs/panel.md "How a button reaches the board"): `step(t)` every
// `period_us` of real time on a thread of its own, t the session's time in µs from 0, so the
// simulated boards' virtual time keeps pace with the wall clock. An exception from a step is
// handed to `failed` and the loop goes on. Stopped (and joined) by stop() or the destructor.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

namespace ap::web {

class PacedLoop {
 public:
  PacedLoop(std::int64_t period_us, std::function<void(std::int64_t t_us)> step,
            std::function<void(const std::string& what)> failed);
  ~PacedLoop();
  PacedLoop(const PacedLoop&) = delete;
  PacedLoop& operator=(const PacedLoop&) = delete;
  void stop();

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace ap::web
