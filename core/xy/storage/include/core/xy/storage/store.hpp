#pragma once
// The parameter store: boots from the newest valid of two FRAM copies and saves by writing
// the other copy, reading it back and comparing. A power cut during a save can only tear the
// copy being written, so the last verified copy survives (seed §4.13, docs/storage.md).
#include <array>
#include <cstdint>

#include "core/xy/storage/fram_device.hpp"
#include "core/xy/storage/fram_map.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/record.hpp"

namespace ap::xy_storage {

// Write + read-back attempts per save before the storage fault (gap G12 decision).
inline constexpr std::uint8_t kMaxSaveAttempts = 3;

enum class StoreStatus : std::uint8_t {
  Ok,
  OutOfRange,     // a value outside its table range; nothing written
  NotPowerOfTwo,  // microsteps not a TMC2130 MRES value; nothing written
  Inconsistent,   // breaks a cross-item rule (speed order, soft-limit order); nothing written
  UnknownId,      // no such item; nothing written
  NotSettable,    // the item is not a user parameter (step counters, meta); nothing written
  StorageFault,   // every attempt failed verification; the previous set stays in use
};

struct SaveResult {
  StoreStatus status;
  std::uint8_t attempts;  // write + read-back rounds used; 0 when nothing was written
  ParamId item;           // the offending item for the range errors
  constexpr bool ok() const noexcept { return status == StoreStatus::Ok; }
};

enum class BootSource : std::uint8_t { CopyA, CopyB, Defaults };

struct BootReport {
  BootSource source;
  std::array<RecordStatus, kCopyCount> copy;
  std::uint32_t sequence;  // of the loaded copy; 0 with defaults
  constexpr bool defaults_used() const noexcept { return source == BootSource::Defaults; }
};

class ParameterStore {
 public:
  // Holds the defaults until boot() has run.
  explicit ParameterStore(SpiBus bus) noexcept;

  // Loads the newest valid copy, or the defaults (reported) when neither is valid. Writes
  // nothing: rewriting the defaults is the supervisor's decision, not a side effect of boot.
  BootReport boot() noexcept;

  const ParameterSet& current() const noexcept { return current_; }
  std::uint32_t sequence() const noexcept { return sequence_; }
  // Latched by a failed save, cleared by the next verified one.
  bool storage_fault() const noexcept { return fault_; }

  // Validates, then writes the copy not holding the current set. Invalid input writes nothing.
  SaveResult save(const ParameterSet& next) noexcept;
  // One user parameter by id: range, rule and cross rules checked against the current set.
  SaveResult set_parameter(std::uint8_t id, std::int64_t value) noexcept;
  // Must return Ok before any motion starts: clears the step-counter validity in FRAM.
  // Skips the write when the flag is already clear.
  SaveResult begin_motion() noexcept;
  // The orderly-shutdown write: the counters and the validity flag in one save.
  SaveResult record_shutdown(std::int32_t step_count_x, std::int32_t step_count_y) noexcept;

 private:
  static constexpr std::uint8_t kNoCopy = 0xFF;
  void read_copy(std::size_t copy, RecordBytes& buf, DecodeResult& out) const noexcept;

  FramDevice fram_;
  ParameterSet current_;
  std::uint32_t sequence_ = 0;
  std::uint8_t active_ = kNoCopy;  // which copy holds current_, or kNoCopy
  bool fault_ = false;
};

}  // namespace ap::xy_storage
