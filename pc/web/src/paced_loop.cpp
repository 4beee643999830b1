// A panel session's real-time loop (paced_loop.hpp).
#include "pc/web/paced_loop.hpp"

#include <chrono>
#include <exception>

namespace ap::web {

PacedLoop::PacedLoop(std::int64_t period_us, std::function<void(std::int64_t)> step,
                     std::function<void(const std::string&)> failed) {
  thread_ = std::thread([this, period_us, step = std::move(step), failed = std::move(failed)] {
    const auto start = std::chrono::steady_clock::now();
    std::int64_t t = 0;
    while (!stop_) {
      try {
        step(t);
      } catch (const std::exception& e) {
        failed(e.what());
      }
      t += period_us;
      std::this_thread::sleep_until(start + std::chrono::microseconds(t));
    }
  });
}

PacedLoop::~PacedLoop() { stop(); }

void PacedLoop::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

}  // namespace ap::web
