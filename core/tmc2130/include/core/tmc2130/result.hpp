#pragma once
// Typed errors for the TMC2130 module and a minimal expected-like carrier (C++20 has no
// std::expected, and the core may not throw).
#include <cstdint>
#include <string_view>

namespace ap::tmc2130 {

enum class Error : std::uint8_t {
  UnknownRegister,    // dynamic lookup by address or name found nothing
  UnknownField,       // dynamic lookup by name found nothing in that register
  ValueOutOfRange,    // field value outside the datasheet range; nothing was sent
  NotWritable,        // R / RC register or field
  FieldNotInRegister, // batch names a field of another register
  DuplicateField,     // batch names the same field twice (ambiguous order)
  BusFailure,         // the SPI transfer function reported a failure
  ReadbackMismatch,   // a readable register kept reading back differently: driver fault
  ChipKeepsResetting, // the chip reset again during every re-initialisation attempt
  CurrentOutOfRange,  // current equation input outside its documented range
  MalformedDatagram,  // decoder input of the wrong length
};

constexpr std::string_view error_name(Error e) {
  switch (e) {
    case Error::UnknownRegister: return "unknown register";
    case Error::UnknownField: return "unknown field";
    case Error::ValueOutOfRange: return "value out of range";
    case Error::NotWritable: return "not writable";
    case Error::FieldNotInRegister: return "field not in register";
    case Error::DuplicateField: return "duplicate field";
    case Error::BusFailure: return "SPI bus failure";
    case Error::ReadbackMismatch: return "read-back mismatch (driver fault)";
    case Error::ChipKeepsResetting: return "chip keeps resetting during re-init";
    case Error::CurrentOutOfRange: return "current out of range";
    case Error::MalformedDatagram: return "malformed datagram";
  }
  return "?";
}

template <class T>
class Result {
 public:
  constexpr Result(T value) : value_(value), ok_(true) {}          // NOLINT: implicit on purpose
  constexpr Result(Error error) : value_{}, error_(error) {}       // NOLINT: implicit on purpose
  constexpr bool ok() const { return ok_; }
  constexpr explicit operator bool() const { return ok_; }
  constexpr const T& value() const { return value_; }
  constexpr const T& operator*() const { return value_; }
  constexpr Error error() const { return error_; }

 private:
  T value_;
  Error error_{};
  bool ok_ = false;
};

}  // namespace ap::tmc2130
