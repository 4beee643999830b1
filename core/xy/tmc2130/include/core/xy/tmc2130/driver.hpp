#pragma once
// TMC2130 driver: shadows, read-modify-write, read-back verification and re-init after a
// chip reset. One instance per chip; the SPI transfer is a plain function pointer plus
// context, so the core needs no virtual interface (and no deleting destructor).
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>

#include "core/xy/tmc2130/datagram.hpp"
#include "core/xy/tmc2130/fields.hpp"
#include "core/xy/tmc2130/regmap.hpp"
#include "core/xy/tmc2130/result.hpp"

namespace ap::xy_tmc2130 {

// One full-duplex 40-bit transfer with chip select framed around it. Returns false when the
// bus itself failed (then rx is not looked at).
struct SpiPort {
  using Transfer = bool (*)(void* context, const Datagram& tx, Datagram& rx);
  Transfer transfer = nullptr;
  void* context = nullptr;
};

class Driver {
 public:
  // A readable register that reads back wrong this many times in a row is a driver fault;
  // the same bound limits re-initialisation rounds when the chip resets during one.
  static constexpr unsigned kMaxWriteAttempts = 3;

  explicit Driver(SpiPort port);

  // Writes every writable register from its shadow (chip reset values until changed), then
  // reads GSTAT to clear the reset flag. Call after power-up.
  Result<SpiStatus> init();

  // Whole-register access. Reads of write-only registers return the shadow without any SPI
  // traffic (the chip would answer 0); reads never modify a shadow.
  Result<std::uint32_t> read(Reg reg);
  Result<SpiStatus> write(Reg reg, std::uint32_t value);

  // Field access. The static forms reject unknown fields and read-only registers at compile
  // time; the dynamic forms return a typed error.
  template <Field F>
  Result<SpiStatus> set(std::int64_t value) {
    static_assert(writable(info(F).reg), "field belongs to a read-only register");
    return set(F, value);
  }
  template <Field F>
  Result<std::int64_t> get() {
    return get(F);
  }
  Result<SpiStatus> set(Field field, std::int64_t value);
  Result<std::int64_t> get(Field field);

  // Several fields of one register in a single datagram; all-or-nothing validation.
  Result<SpiStatus> update(Reg reg, std::span<const FieldValue> values);
  Result<SpiStatus> update(Reg reg, std::initializer_list<FieldValue> values) {
    return update(reg, std::span<const FieldValue>(values.begin(), values.size()));
  }

  // Reads GSTAT (which clears it) and re-initialises if the chip has been reset.
  Result<SpiStatus> check_reset();

  std::uint32_t shadow(Reg reg) const { return shadow_[index_of(reg)]; }
  SpiStatus last_status() const { return last_status_; }
  unsigned resets_recovered() const { return resets_recovered_; }

 private:
  bool transfer(const Request& req, Reply& reply);
  Result<std::uint32_t> read_chip(Reg reg);
  Result<SpiStatus> write_verified(Reg reg, std::uint32_t value);
  Result<SpiStatus> restore();
  Result<SpiStatus> finish(Result<SpiStatus> r);

  SpiPort port_;
  std::array<std::uint32_t, kRegisterCount> shadow_{};
  SpiStatus last_status_{};
  bool reset_seen_ = false;
  bool restoring_ = false;
  unsigned resets_recovered_ = 0;
};

}  // namespace ap::xy_tmc2130
