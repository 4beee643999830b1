#pragma once
// An I2C bus as the controller sees it: every transaction goes to each attached device in
// turn until one acknowledges its address (a device answers AddressNack for any address not
// its own); nobody acknowledging is AddressNack, like an open-drain bus with no target.
// Fault injection (a transaction that fails before reaching any device) and the log are test
// hooks, off by default.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/xy/i2c/port.hpp"

namespace ap::model::xy_i2c {

namespace bus = ap::xy_i2c;

class Device {
 public:
  virtual ~Device() = default;
  virtual bus::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx,
                               std::span<std::uint8_t> rx) = 0;
};

class Bus {
 public:
  void attach(Device& d) { devices_.push_back(&d); }

  bus::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx);

  // The `n`-th transaction from now (0 = the next one) fails with `status` without reaching
  // any device; with `forever` every transaction from then on fails.
  void fail_at(unsigned n, bus::Status status, bool forever = false);
  void heal() { fail_at_.reset(); }

  struct Transaction {
    std::uint8_t address;
    std::vector<std::uint8_t> tx;
    std::size_t rx_len;
    bus::Status status;
  };
  const std::vector<Transaction>& log() const { return log_; }
  void clear_log() { log_.clear(); }
  // Transactions that wrote more than a register pointer (register writes).
  unsigned writes() const;

  static bus::Status port_transfer(void* context, std::uint8_t address, std::span<const std::uint8_t> tx,
                                   std::span<std::uint8_t> rx);
  bus::Port port() { return {&Bus::port_transfer, this}; }

 private:
  std::vector<Device*> devices_;
  std::optional<unsigned> fail_at_;
  bus::Status fail_status_ = bus::Status::BusError;
  bool fail_forever_ = false;
  std::vector<Transaction> log_;
};

}  // namespace ap::model::xy_i2c
