#include "models/tmc2130/device.hpp"

namespace ap::model::tmc2130 {

namespace {
// Datasheet 5.5, register 0x6C CHOPCONF. Stated here, not read from core/tmc2130's table.
constexpr std::uint32_t kToffMask = 0x0000000FU;  // bits 3..0
constexpr unsigned kMresShift = 24;               // bits 27..24
constexpr std::uint32_t kMresMask = 0xFU;
constexpr std::uint32_t kMresFullStep = 8;        // %1000; %1001..%1111 are not defined
}  // namespace

bool Device::power_stage_on() const {
  return !drv_enn_high_ && (regs_[chip::index_of(chip::Reg::CHOPCONF)] & kToffMask) != 0;
}

std::int32_t Device::microsteps() const {
  const std::uint32_t mres = (regs_[chip::index_of(chip::Reg::CHOPCONF)] >> kMresShift) & kMresMask;
  // The datasheet defines MRES only up to %1000; a larger value is taken as full step, the
  // coarsest the chip has (the firmware never writes one: its field range stops at 8).
  return std::int32_t{256} >> (mres > kMresFullStep ? kMresFullStep : mres);
}

std::int64_t Device::step(std::int64_t edges, int dir) const {
  if (!power_stage_on()) return 0;
  return static_cast<std::int64_t>(dir) * edges * (256 / microsteps());
}

void Device::power_cycle() {
  for (std::size_t i = 0; i < chip::kRegisterCount; ++i) regs_[i] = chip::kRegisters[i].reset;
  latch_ = 0;
}

std::uint32_t Device::read_view(std::uint8_t addr) const {
  const auto idx = chip::register_index(addr);
  // Unused addresses and write-only registers return 0 (datasheet 5: write-only
  // registers cannot be read back), which is exactly why drivers need shadows.
  if (!idx || !chip::readable(chip::kRegisters[*idx].access)) return 0;
  return regs_[*idx];
}

std::uint8_t Device::status_byte() const {
  const std::uint32_t gstat = regs_[chip::index_of(chip::Reg::GSTAT)];
  const std::uint32_t drv = regs_[chip::index_of(chip::Reg::DRV_STATUS)];
  return chip::encode_status({(gstat & 1u) != 0, (gstat & 2u) != 0, ((drv >> 24) & 1u) != 0,
                              ((drv >> 31) & 1u) != 0});
}

chip::Datagram Device::transfer(const chip::Datagram& mosi) {
  const chip::Request req = chip::decode_request(mosi);
  // The reply is shifted out while the request shifts in: status now, data from before.
  const chip::Datagram miso{status_byte(), static_cast<std::uint8_t>(latch_ >> 24),
                            static_cast<std::uint8_t>(latch_ >> 16),
                            static_cast<std::uint8_t>(latch_ >> 8), static_cast<std::uint8_t>(latch_)};
  log_.push_back({req.write, req.address, req.data});
  const auto idx = chip::register_index(req.address);
  if (req.write) {
    if (idx && chip::writable(chip::kRegisters[*idx].access)) {
      const chip::Reg reg = chip::kRegisters[*idx].reg;
      std::uint32_t v = req.data;
      if (corrupt_count_ > 0 && reg == corrupt_reg_) {
        v ^= corrupt_flip_;
        --corrupt_count_;
      }
      regs_[*idx] = v & chip::implemented_mask(reg);
    }
    latch_ = read_view(req.address);
  } else {
    latch_ = read_view(req.address);
    if (idx && chip::kRegisters[*idx].access == chip::Access::RC) regs_[*idx] = 0;
  }
  if (power_cycle_in_ > 0 && --power_cycle_in_ == 0) power_cycle();
  return miso;
}

void Device::set_input(chip::Reg reg, std::uint32_t value) {
  regs_[chip::index_of(reg)] = value & chip::implemented_mask(reg);
}

void Device::corrupt_writes(chip::Reg reg, std::uint32_t flip, unsigned count) {
  corrupt_reg_ = reg;
  corrupt_flip_ = flip;
  corrupt_count_ = count;
}

unsigned Device::reads_of(chip::Reg reg) const {
  unsigned n = 0;
  for (const auto& a : log_) n += (!a.write && a.address == chip::address(reg)) ? 1u : 0u;
  return n;
}

unsigned Device::writes_of(chip::Reg reg) const {
  unsigned n = 0;
  for (const auto& a : log_) n += (a.write && a.address == chip::address(reg)) ? 1u : 0u;
  return n;
}

bool Device::spi(void* context, const chip::Datagram& tx, chip::Datagram& rx) {
  rx = static_cast<Device*>(context)->transfer(tx);
  return true;
}

}  // namespace ap::model::tmc2130
