// The parameter store (core/xy/storage) driven by a fuzz-decoded script of its operations on
// the FRAM model, with power cuts at any SPI byte and transient bit flips, then reboots.
// Oracles: a save that reports Ok survives a reboot; after a power cut the reboot loads the
// last verified set or the one being written, never a mixture; a save reported failed with
// the power on never loads; an operation refused for a range or rule error writes nothing;
// the set in use is always valid. Faults combine freely (no single-fault mode): a bit flip
// stays armed through saves and power cuts until a reboot or op 7 clears it.
//
// Ops, one byte each (low 3 bits = op) plus arguments:
//   0  set_parameter: id byte, value (1 byte selector + 4 bytes; see value_of)
//   1  begin_motion
//   2  record_shutdown: x, y (4 bytes each)
//   3  power cut after k SPI bytes (2 bytes) during the next set/shutdown op, then reboot
//      (armed bit flips stay armed until the reboot: a flip and a cut are one double fault)
//   4  reboot
//   5  bit flip on write / on read (replacing any armed one): copy, address, mask, count
//   6  save(current) with step_counts_valid toggled
//   7  clear the faults
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include "core/xy/storage/fram_map.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/record.hpp"
#include "core/xy/storage/store.hpp"
#include "models/xy/fram/mb85rs256b.hpp"
#include "fuzz/script_reader.hpp"

using namespace ap::xy_storage;
using ap::model::Mb85rs256b;

namespace {

[[noreturn]] void violation(const char* what) {
  std::fprintf(stderr, "store_ops fuzz: property violated: %s\n", what);
  std::abort();
}

using ap::fuzz::Reader;

struct Harness {
  std::unique_ptr<Mb85rs256b> chip = std::make_unique<Mb85rs256b>();
  std::optional<ParameterStore> store;
  ParameterSet committed{};                // what a reboot must load (no fault pending)
  std::optional<ParameterSet> maybe;       // a save that may or may not have landed

  void reboot() {
    chip->clear_faults();
    chip->power_on();
    store.emplace(chip->bus());
    (void)store->boot();
    const ParameterSet& now = store->current();
    if (!validate(now).ok()) violation("booted set not valid");
    if (!(now == committed || (maybe && now == *maybe))) violation("reboot loaded neither the last verified set nor the one being written");
    committed = now;
    maybe.reset();
  }

  // Records the outcome of one writing operation of the store.
  void after(const SaveResult& r, const ParameterSet& before, const std::optional<ParameterSet>& intended) {
    const ParameterSet& now = store->current();
    if (!validate(now).ok()) violation("set in use not valid");
    if (r.ok()) {
      if (intended && !(now == *intended)) violation("Ok save left another set in use");
      committed = now;
      maybe.reset();
      return;
    }
    if (!(now == before)) violation("a refused or failed save changed the set in use");
    // Only a cut may leave the failed save's set to the reboot (its record may have landed
    // before the power died); a save reported failed with the power on must never load.
    if (r.status == StoreStatus::StorageFault && intended && !chip->powered()) maybe = *intended;
  }

  static std::int64_t value_of(Reader& r, const ParameterSet& cur, ParamId id) {
    const std::uint8_t sel = r.u8();
    const std::int32_t raw = r.i32();
    const auto now = get_field(cur, id);
    switch (sel & 3U) {
      case 0: return raw;
      case 1: return now.value_or(0) + (raw % 64);
      case 2: return now.value_or(0) * 2;
      default: return static_cast<std::int64_t>(1) << (static_cast<std::uint32_t>(raw) % 10);
    }
  }

  void set_op(Reader& r) {
    const std::uint8_t id = r.u8() % static_cast<std::uint8_t>(kItemCount + 2);
    const ParameterSet before = store->current();
    const std::int64_t v = id < kItemCount ? value_of(r, before, static_cast<ParamId>(id)) : r.i32();
    std::optional<ParameterSet> intended;
    if (id < kItemCount) {
      ParameterSet next = before;
      if (set_field(next, static_cast<ParamId>(id), v)) intended = next;
    }
    const SaveResult res = store->set_parameter(id, v);
    after(res, before, intended);
  }

  void shutdown_op(Reader& r) {
    const ParameterSet before = store->current();
    ParameterSet next = before;
    next.step_count_x = r.i32();
    next.step_count_y = r.i32();
    next.step_counts_valid = true;
    const SaveResult res = store->record_shutdown(next.step_count_x, next.step_count_y);
    after(res, before, next);
  }

  void run(const std::uint8_t* data, std::size_t size) {
    chip->power_on();
    store.emplace(chip->bus());
    (void)store->boot();
    committed = store->current();
    Reader r{data, size};
    int ops = 0;
    while (r.more() && ++ops < 200) {
      const std::uint8_t op = r.u8();
      switch (op & 7U) {
        case 0: set_op(r); break;
        case 1: {
          const ParameterSet before = store->current();
          ParameterSet next = before;
          next.step_counts_valid = false;
          after(store->begin_motion(), before, next);
          break;
        }
        case 2: shutdown_op(r); break;
        case 3: {
          const ParameterSet before = store->current();
          // Armed bit flips stay armed through the cut: a flip and a cut in the same save (and
          // the torn saves after it) are the double faults docs/storage.md argues the store
          // survives; the reboot clears them.
          chip->arm_power_cut_after(r.u16() % 512U);
          // Whatever the store reports while the power dies, the reboot decides.
          if ((op & 8U) != 0) {
            shutdown_op(r);
          } else {
            set_op(r);
          }
          if (!(store->current() == before)) maybe = store->current();
          reboot();
          break;
        }
        case 4: reboot(); break;
        case 5: {
          const std::uint16_t base = kCopyBase[r.u8() & 1U];
          const auto addr = static_cast<std::uint16_t>(base + r.u8() % kRecordSize);
          const std::uint8_t mask = static_cast<std::uint8_t>(r.u8() | 1U);
          const std::uint32_t count = 1 + r.u8() % 4;
          // One fault at a time: a write flip and a read flip of the same bits cancel in the
          // read-back, which no store can detect (and no real part does).
          chip->clear_faults();
          if ((op & 8U) != 0) {
            chip->flip_on_read(addr, mask, count);
          } else {
            chip->flip_on_write(addr, mask, count);
          }
          break;
        }
        case 6: {
          const ParameterSet before = store->current();
          ParameterSet next = before;
          next.step_counts_valid = !next.step_counts_valid;
          after(store->save(next), before, next);
          break;
        }
        default:
          chip->clear_faults();
          break;
      }
    }
    reboot();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Harness h;
  h.run(data, size);
  return 0;
}
