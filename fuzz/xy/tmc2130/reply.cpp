// Fuzz target tmc2130_reply: every SPI reply the driver sees comes from the input, so the
// status byte (reset flags at any moment, driver errors) and the data (read-back mismatches,
// garbage GSTAT) are adversarial. Oracles, beyond the sanitizers:
//   - a successful field write leaves the field's value in the shadow;
//   - reading a write-only register never changes its shadow and never touches the bus;
//   - a rejected out-of-range value sends nothing;
//   - every decoded reply re-encodes to the same status bits.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/xy/tmc2130/driver.hpp"

namespace {

namespace chip = ap::xy_tmc2130;

struct Feed {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t pos = 0;
  unsigned transfers = 0;

  std::uint8_t next() { return pos < size ? data[pos++] : 0; }
};

bool spi(void* context, const chip::Datagram&, chip::Datagram& rx) {
  auto* f = static_cast<Feed*>(context);
  ++f->transfers;
  const std::uint8_t first = f->next();
  if (first == 0xEE) return false;  // a bus failure, on demand
  rx[0] = first;
  for (std::size_t i = 1; i < rx.size(); ++i) rx[i] = f->next();
  const auto st = chip::decode_status(rx[0]);
  if (chip::encode_status(st) != (rx[0] & 0x0F)) std::abort();
  return true;
}

void check(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Feed feed{data, size};
  chip::Driver drv(chip::SpiPort{&spi, &feed});
  (void)drv.init();
  // The first bytes choose the operations; the rest are the chip's replies.
  for (int step = 0; step < 16 && feed.pos < feed.size; ++step) {
    const std::uint8_t op = feed.next();
    const auto& f = chip::kFields[feed.next() % chip::kFieldCount];
    const std::int64_t span = f.max - f.min + 1;
    const std::int64_t v = f.min + static_cast<std::int64_t>(feed.next() | (feed.next() << 8)) % span;
    switch (op % 5) {
      case 0: {
        if (!chip::writable(f.reg)) break;
        if (drv.set(f.field, v)) check(chip::field_get(drv.shadow(f.reg), f.field) == v);
        break;
      }
      case 1: {
        const std::uint32_t before = drv.shadow(f.reg);
        const unsigned t = feed.transfers;
        (void)drv.get(f.field);
        if (chip::info(f.reg).access == chip::Access::W) {
          check(drv.shadow(f.reg) == before);
          check(feed.transfers == t);
        }
        break;
      }
      case 2: {
        const unsigned t = feed.transfers;
        const auto r = drv.set(f.field, f.max + 1);
        check(!r && feed.transfers == t);
        break;
      }
      case 3:
        (void)drv.check_reset();
        break;
      default:
        (void)drv.read(f.reg);
        break;
    }
  }
  return 0;
}
