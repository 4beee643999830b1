#include "core/xy/tmc2130/driver.hpp"

namespace ap::xy_tmc2130 {

Driver::Driver(SpiPort port) : port_(port) {
  for (std::size_t i = 0; i < kRegisterCount; ++i) shadow_[i] = kRegisters[i].reset;
}

bool Driver::transfer(const Request& req, Reply& reply) {
  if (port_.transfer == nullptr) return false;
  const Datagram tx = encode(req);
  Datagram rx{};
  if (!port_.transfer(port_.context, tx, rx)) return false;
  reply = decode_reply(rx);
  last_status_ = reply.status;
  if (reply.status.reset_flag) reset_seen_ = true;
  return true;
}

Result<std::uint32_t> Driver::read_chip(Reg reg) {
  // Pipelined read: the first reply carries whatever the previous access latched, the
  // second carries this register.
  const Request req{false, address(reg), 0};
  Reply reply{};
  if (!transfer(req, reply) || !transfer(req, reply)) return Error::BusFailure;
  return reply.data;
}

Result<SpiStatus> Driver::write_verified(Reg reg, std::uint32_t value) {
  const std::size_t idx = index_of(reg);
  const bool verify = readable(reg);
  const std::uint32_t implemented = implemented_mask(reg);
  for (unsigned attempt = 0; attempt < kMaxWriteAttempts; ++attempt) {
    Reply reply{};
    if (!transfer({true, address(reg), value}, reply)) return Error::BusFailure;
    // Only now has the value gone out; a shadow updated earlier would lie after a bus error.
    shadow_[idx] = value;
    if (!verify) return last_status_;
    const auto back = read_chip(reg);
    if (!back) return back.error();
    if (((*back ^ value) & implemented) == 0) return last_status_;
  }
  return Error::ReadbackMismatch;
}

Result<SpiStatus> Driver::restore() {
  restoring_ = true;
  const auto done = [this](Result<SpiStatus> r) {
    restoring_ = false;
    return r;
  };
  for (unsigned round = 0; round < kMaxWriteAttempts; ++round) {
    // Clear the flag before rewriting, so a reset during the rewrite shows up again below.
    const auto cleared = read_chip(Reg::GSTAT);
    if (!cleared) return done(cleared.error());
    // Every writable register, in address order, from the shadow; the chip lost them all.
    for (const auto& r : kRegisters) {
      if (!writable(r.access)) continue;
      const auto w = write_verified(r.reg, shadow_[index_of(r.reg)]);
      if (!w) return done(w);
    }
    const auto gstat = read_chip(Reg::GSTAT);
    if (!gstat) return done(gstat.error());
    if (field_get(*gstat, Field::GSTAT_reset) == 0) {
      reset_seen_ = false;
      ++resets_recovered_;
      return done(last_status_);
    }
  }
  return done(Error::ChipKeepsResetting);
}

Result<SpiStatus> Driver::finish(Result<SpiStatus> r) {
  // A reset flag seen in any reply means the chip's registers are back at reset values.
  if (reset_seen_ && !restoring_) {
    const auto rr = restore();
    if (!rr) return rr;
  }
  return r;
}

Result<SpiStatus> Driver::init() {
  reset_seen_ = true;
  return finish(last_status_);
}

Result<SpiStatus> Driver::check_reset() {
  const auto gstat = read_chip(Reg::GSTAT);
  if (!gstat) return gstat.error();
  if (field_get(*gstat, Field::GSTAT_reset) != 0) reset_seen_ = true;
  return finish(last_status_);
}

Result<std::uint32_t> Driver::read(Reg reg) {
  if (!readable(reg)) return shadow_[index_of(reg)];
  const auto r = read_chip(reg);
  if (!r) return r;
  const bool was_reset = reset_seen_;
  const auto f = finish(last_status_);
  if (!f) return f.error();
  // A value read from a chip that had just reset is a reset value, not ours: read again
  // after the re-init. GSTAT is the exception, its flags are the record of that event.
  if (was_reset && info(reg).access != Access::RC) return read_chip(reg);
  return r;
}

Result<SpiStatus> Driver::write(Reg reg, std::uint32_t value) {
  if (!writable(reg)) return Error::NotWritable;
  return finish(write_verified(reg, value));
}

Result<SpiStatus> Driver::update(Reg reg, std::span<const FieldValue> values) {
  if (!writable(reg)) return Error::NotWritable;
  // Validate before any traffic, so bad input changes nothing, not even the chip.
  const auto check = fields_set(0, reg, values.data(), values.data() + values.size());
  if (!check) return check.error();

  std::uint32_t base = shadow_[index_of(reg)];
  if (readable(reg)) {
    auto chip = read_chip(reg);
    if (!chip) return chip.error();
    if (reset_seen_) {
      // The chip just came out of reset: its contents are reset values, not ours.
      const auto rr = restore();
      if (!rr) return rr;
      chip = read_chip(reg);
      if (!chip) return chip.error();
    }
    base = *chip;
  }
  const auto next = fields_set(base, reg, values.data(), values.data() + values.size());
  return finish(write_verified(reg, *next));
}

Result<SpiStatus> Driver::set(Field field, std::int64_t value) {
  const FieldValue fv{field, value};
  return update(info(field).reg, std::span<const FieldValue>(&fv, 1));
}

Result<std::int64_t> Driver::get(Field field) {
  const auto word = read(info(field).reg);
  if (!word) return word.error();
  return field_get(*word, field);
}

}  // namespace ap::xy_tmc2130
