#include "models/xy/tmc2130/device.hpp"

#include <algorithm>

namespace ap::model::xy_tmc2130 {

namespace {
namespace ds = datasheet;
// Datasheet 5.5, register 0x6C CHOPCONF. Stated here, not read from core/xy/tmc2130's table.
constexpr std::uint32_t kToffMask = 0x0000000FU;  // bits 3..0
constexpr unsigned kMresShift = 24;               // bits 27..24
constexpr std::uint32_t kMresMask = 0xFU;
constexpr std::uint32_t kMresFullStep = 8;        // %1000; %1001..%1111 are not defined
// DRV_STATUS (0x6F) bits, datasheet 5.5.
constexpr std::uint32_t kStst = 1U << 31, kS2gb = 1U << 28, kS2ga = 1U << 27, kOtpw = 1U << 26, kOt = 1U << 25,
                        kStallGuard = 1U << 24;
constexpr unsigned kCsActualShift = 16;
constexpr std::uint32_t kCsActualMask = 0x1FU << kCsActualShift;
// GCONF (0x00) bits, datasheet 5.1.
constexpr std::uint32_t kDiag0Error = 1U << 5, kDiag0Otpw = 1U << 6, kDiag0Stall = 1U << 7, kDiag1Stall = 1U << 8,
                        kDiag0PushPull = 1U << 12, kDiag1PushPull = 1U << 13;
// IHOLD_IRUN (0x10): IHOLD 4..0, IRUN 12..8, IHOLDDELAY 19..16; TPOWERDOWN (0x11) 7..0.
constexpr std::int64_t kClockHz = 12'000'000;
constexpr std::int64_t kStandstillClocks = std::int64_t{1} << 20;
constexpr std::int64_t kDelayUnitClocks = std::int64_t{1} << 18;
}  // namespace

bool Device::power_stage_on() const {
  const std::uint32_t drv = drv_status_input_;
  // ot: "the driver is shut down due to overtemperature"; a short stays off until cleared.
  return !drv_enn_high_ && (regs_[ds::addr::CHOPCONF] & kToffMask) != 0 && (drv & kOt) == 0 && !short_latched_;
}

void Device::elapse_us(std::int64_t us) {
  if (clocks_since_step_ < (std::int64_t{1} << 40)) clocks_since_step_ += us * (kClockHz / 1'000'000);
}

bool Device::standstill() const { return clocks_since_step_ >= kStandstillClocks; }

std::int32_t Device::current_scale() const {
  if (!power_stage_on()) return 0;
  const std::uint32_t ihold_irun = regs_[ds::addr::IHOLD_IRUN];
  const auto ihold = static_cast<std::int32_t>(ihold_irun & 0x1FU);
  const auto irun = static_cast<std::int32_t>((ihold_irun >> 8) & 0x1FU);
  const auto delay = static_cast<std::int64_t>((ihold_irun >> 16) & 0xFU);
  const auto tpowerdown = static_cast<std::int64_t>(regs_[ds::addr::TPOWERDOWN] & 0xFFU);
  const std::int64_t after = clocks_since_step_ - tpowerdown * kDelayUnitClocks;
  if (after < 0 || irun <= ihold) return after < 0 ? irun : ihold;
  if (delay == 0) return ihold;
  const std::int64_t down = after / (delay * kDelayUnitClocks) + 1;
  return static_cast<std::int32_t>(std::max<std::int64_t>(ihold, irun - down));
}

std::uint32_t Device::drv_status_view() const {
  std::uint32_t v = drv_status_input_ & ~(kStst | kCsActualMask);
  if (standstill()) v |= kStst;
  v |= (static_cast<std::uint32_t>(current_scale()) << kCsActualShift) & kCsActualMask;
  return v;
}

bool Device::diag0_asserted() const {
  const std::uint32_t g = regs_[ds::addr::GCONF];
  const std::uint32_t d = drv_status_input_;
  return ((g & kDiag0Error) != 0 && ((d & (kOt | kS2ga | kS2gb)) != 0 || short_latched_)) ||
         ((g & kDiag0Otpw) != 0 && (d & kOtpw) != 0) || ((g & kDiag0Stall) != 0 && (d & kStallGuard) != 0);
}

bool Device::diag1_asserted() const {
  const std::uint32_t g = regs_[ds::addr::GCONF];
  return (g & kDiag1Stall) != 0 && (drv_status_input_ & kStallGuard) != 0;
}

bool Device::diag0_level() const {
  const bool push_pull = (regs_[ds::addr::GCONF] & kDiag0PushPull) != 0;
  return push_pull ? diag0_asserted() : !diag0_asserted();
}

bool Device::diag1_level() const {
  const bool push_pull = (regs_[ds::addr::GCONF] & kDiag1PushPull) != 0;
  return push_pull ? diag1_asserted() : !diag1_asserted();
}

std::int32_t Device::microsteps() const {
  const std::uint32_t mres = (regs_[ds::addr::CHOPCONF] >> kMresShift) & kMresMask;
  // The datasheet defines MRES only up to %1000; a larger value is taken as full step, the
  // coarsest the chip has (the firmware never writes one: its field range stops at 8).
  return std::int32_t{256} >> (mres > kMresFullStep ? kMresFullStep : mres);
}

std::int64_t Device::step(std::int64_t edges, int dir) {
  if (drv_enn_high_) short_latched_ = false;  // DRV_ENN clears the short latch
  if (edges > 0) clocks_since_step_ = 0;      // the chip sees the edges whether it drives or not
  if (!power_stage_on()) return 0;
  return static_cast<std::int64_t>(dir) * edges * (256 / microsteps());
}

void Device::power_cycle() {
  // Every register to its power-up value (datasheet table); unused addresses hold 0.
  regs_.fill(0);
  for (const auto& f : ds::kRegisters) regs_[f.address] = f.reset;
  latch_ = 0;
  short_latched_ = false;
  drv_status_input_ = 0x80000000U;
  clocks_since_step_ = std::int64_t{1} << 40;
}

std::uint32_t Device::read_view(std::uint8_t addr) const {
  const ds::RegisterFact* f = ds::fact(addr);
  // Unused addresses and write-only registers return 0 (datasheet 5: write-only
  // registers cannot be read back), which is exactly why drivers need shadows.
  if (f == nullptr || !ds::readable(f->access)) return 0;
  if (f->address == ds::addr::DRV_STATUS) return drv_status_view();
  return regs_[f->address];
}

std::uint8_t Device::status_byte() const {
  const std::uint32_t gstat = regs_[ds::addr::GSTAT];
  const std::uint32_t drv = drv_status_view();
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
  const ds::RegisterFact* f = ds::fact(req.address);
  if (req.write) {
    // A write to a read-only register or an unused address changes nothing.
    if (f != nullptr && ds::writable(f->access)) {
      std::uint32_t v = req.data;
      if (corrupt_count_ > 0 && f->address == slot(corrupt_reg_)) {
        v ^= corrupt_flip_;
        --corrupt_count_;
      }
      regs_[f->address] = v & f->implemented;  // reserved bits are not kept
      if (f->address == ds::addr::CHOPCONF && (regs_[f->address] & kToffMask) == 0) short_latched_ = false;
    }
    latch_ = read_view(req.address);
  } else {
    latch_ = read_view(req.address);
    if (f != nullptr && ds::clears_on_read(f->access)) regs_[f->address] = 0;  // R+C: GSTAT
  }
  if (power_cycle_in_ > 0 && --power_cycle_in_ == 0) power_cycle();
  return miso;
}

void Device::set_input(chip::Reg reg, std::uint32_t value) {
  // Only the bits the datasheet defines in that register can be measured.
  const ds::RegisterFact* f = ds::fact(slot(reg));
  regs_[slot(reg)] = f != nullptr ? value & f->implemented : 0U;
  if (slot(reg) == ds::addr::DRV_STATUS) {
    drv_status_input_ = regs_[slot(reg)];
    if ((drv_status_input_ & (kS2ga | kS2gb)) != 0) short_latched_ = true;
  }
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

}  // namespace ap::model::xy_tmc2130
