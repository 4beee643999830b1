#pragma once
// Typed errors for the TMC2130 module, carried by the core's one Result template.
#include <cstdint>
#include <string_view>

#include "core/result/result.hpp"

namespace ap::xy_tmc2130 {

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
using Result = ap::Result<T, Error>;

}  // namespace ap::xy_tmc2130
