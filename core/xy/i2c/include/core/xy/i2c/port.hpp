#pragma once
// The I2C bus as the sensor drivers see it (docs/sensors.md "The I2C port"): one combined
// transaction per call, a plain function pointer plus context like xy_tmc2130::SpiPort, so the
// core needs no virtual interface and the firmware, the device models and the tests can all
// stand behind it.
#include <cstdint>
#include <span>

namespace ap::xy_i2c {

// How a transaction ended. Every value but Ok means the transaction did not complete; the
// bytes of `rx` are then unspecified and the drivers never look at them.
enum class Status : std::uint8_t {
  Ok,
  NoPort,       // no transfer function wired (a test or board that leaves the bus out)
  AddressNack,  // nobody acknowledged the 7-bit address: device absent, unpowered, wrong strap
  DataNack,     // the device acknowledged its address but refused a written byte
  BusError,     // arbitration lost, stuck bus, timeout: the controller gave up
};

// One transaction to the 7-bit `address`: START, address+W, every byte of `tx`, then, when
// `rx` is not empty, a repeated START, address+R and `rx.size()` bytes read, then STOP.
// An empty `tx` is a plain read (the device answers from its current register pointer).
struct Port {
  using Transfer = Status (*)(void* context, std::uint8_t address, std::span<const std::uint8_t> tx,
                              std::span<std::uint8_t> rx);
  Transfer transfer = nullptr;
  void* context = nullptr;
};

inline constexpr std::uint8_t kAddressMask = 0x7F;

// A failed transaction as a driver's own error: every sensor driver's error enum names these
// four cases, and a bus fault maps onto them the same way for each.
template <class E>
constexpr E error_of(Status s) {
  switch (s) {
    case Status::NoPort: return E::NoPort;
    case Status::AddressNack: return E::AddressNack;
    case Status::DataNack: return E::DataNack;
    case Status::Ok:
    case Status::BusError: break;
  }
  return E::BusError;
}

inline Status transfer(const Port& port, std::uint8_t address, std::span<const std::uint8_t> tx,
                       std::span<std::uint8_t> rx) {
  if (port.transfer == nullptr) return Status::NoPort;
  return port.transfer(port.context, static_cast<std::uint8_t>(address & kAddressMask), tx, rx);
}

}  // namespace ap::xy_i2c
