#pragma once
// The charger-circuit disconnect (thesis §7.9.3: the firmware can disconnect the charging
// circuit; §7.9.4: temperature affects charger and battery, an automatic reaction to limits is
// future work). The thesis gives no rule; ours is docs/board.md "Charger disconnect": a
// lithium cell must not be charged below 0 °C or above 45 °C (the charge temperature range of
// common Li-ion cell datasheets), so the board disconnects the charger while its TMP117 reads
// outside that window and reconnects it 2 °C inside it. Without a valid temperature the
// charger stays connected: its own IC protects the cell, and a lost sensor must not stop a
// unit from ever charging again.
#include <cstdint>

namespace ap::xy_board {

inline constexpr std::int32_t kChargeMinMc = 0;
inline constexpr std::int32_t kChargeMaxMc = 45'000;
inline constexpr std::int32_t kChargeHysteresisMc = 2'000;

constexpr bool charging_allowed(bool allowed_now, bool temperature_valid, std::int32_t mc) {
  if (!temperature_valid) return true;
  if (allowed_now) return mc >= kChargeMinMc && mc <= kChargeMaxMc;
  return mc >= kChargeMinMc + kChargeHysteresisMc && mc <= kChargeMaxMc - kChargeHysteresisMc;
}

}  // namespace ap::xy_board
