#include "models/xy/i2c/bus.hpp"

namespace ap::model::xy_i2c {

bus::Status Bus::transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  bus::Status status = bus::Status::AddressNack;
  if (fail_at_) {
    if (*fail_at_ == 0) {
      status = fail_status_;
      if (!fail_forever_) fail_at_.reset();
      log_.push_back({address, {tx.begin(), tx.end()}, rx.size(), status});
      return status;
    }
    --*fail_at_;
  }
  for (Device* d : devices_) {
    status = d->transfer(address, tx, rx);
    if (status != bus::Status::AddressNack) break;
  }
  log_.push_back({address, {tx.begin(), tx.end()}, rx.size(), status});
  return status;
}

void Bus::fail_at(unsigned n, bus::Status status, bool forever) {
  fail_at_ = n;
  fail_status_ = status;
  fail_forever_ = forever;
}

unsigned Bus::writes() const {
  unsigned n = 0;
  for (const auto& t : log_) n += t.tx.size() > 1 ? 1u : 0u;
  return n;
}

bus::Status Bus::port_transfer(void* context, std::uint8_t address, std::span<const std::uint8_t> tx,
                               std::span<std::uint8_t> rx) {
  return static_cast<Bus*>(context)->transfer(address, tx, rx);
}

}  // namespace ap::model::xy_i2c
