// Start position (thesis section 7.7.2): the step counter is seeded once at power-up, from the
// absolute encoder by eq. 7-2 or from the counter saved at shutdown when its validity flag is
// set; otherwise the axis is unhomed and must home (gap G19) before positioning.
#pragma once

#include <cstdint>

#include "core/xy/axis/axis.hpp"

namespace ap::xy_axis {

inline constexpr int32_t kEncoderCounts = 16384;  // REN: RLS Orbis 14-bit (gap G18)

// turns: the multi-turn count AHO, sign-extended (negative turns are below the encoder zero);
// counts: PVO in [0, 16383]; valid: the encoder's own status bits said the data are good.
struct EncoderReading {
  int32_t turns = 0;
  uint16_t counts = 0;
  uint8_t valid = 0;
};

struct SavedCounter {
  int32_t pos = 0;
  uint8_t valid = 0;
};

struct StartPosition {
  int32_t pos = 0;
  uint8_t homed = 0;
  Error error = Error::None;
};

// Eq. 7-2: AHP = AHO*MNK*KNO + (PVO*MNK*KNO) / REN, the second term multiplied before the
// floor division. usteps_per_rev <= 256000, |turns| < 2^31: |AHO*rev| < 2^49, int64.
// Floor division keeps negative turns consistent: turns=-1, counts=8192 -> -rev/2.
[[nodiscard]] constexpr StartPosition encoder_to_usteps(const EncoderReading& e, int32_t usteps_rev) {
  if (usteps_rev < 1 || usteps_rev > 256'000 || e.counts >= kEncoderCounts) {
    return {0, 0, Error::BadCommand};
  }
  const int64_t whole = static_cast<int64_t>(e.turns) * usteps_rev;
  const int64_t part = static_cast<int64_t>(e.counts) * usteps_rev / kEncoderCounts;
  const int64_t p = whole + part;
  if (p < -kPosMax || p > kPosMax) {
    return {0, 0, Error::OutOfLimits};
  }
  return {static_cast<int32_t>(p), 1, Error::None};
}

// The encoder measures where the carriage is; the saved counter only says where it was at
// shutdown, so a valid encoder reading wins.
[[nodiscard]] constexpr StartPosition start_position(const EncoderReading* enc, const SavedCounter& saved,
                                                     int32_t usteps_rev) {
  if (enc != nullptr && enc->valid != 0) {
    const StartPosition s = encoder_to_usteps(*enc, usteps_rev);
    if (s.error == Error::None) {
      return s;
    }
  }
  if (saved.valid != 0 && saved.pos >= -kPosMax && saved.pos <= kPosMax) {
    return {saved.pos, 1, Error::None};
  }
  return {0, 0, Error::NotHomed};
}

// The encoder count (turns * REN + angle) that eq. 7-2 turns back into `pos`: the smallest c
// with floor(c * rev / REN) >= pos, so encoder_to_usteps() of it gives `pos` exactly when
// rev <= REN and at most rev / REN microsteps more above (docs/motion.md "Homing and the encoder
// zero"). |pos| <= kPosMax, 1 <= usteps_rev <= 256000: |pos * REN| < 2^45, int64.
[[nodiscard]] constexpr int64_t encoder_counts_for(int32_t pos, int32_t usteps_rev) {
  const int64_t rev = usteps_rev;
  const int64_t n = static_cast<int64_t>(pos) * kEncoderCounts;
  return n >= 0 ? (n + rev - 1) / rev : -((-n) / rev);
}

// The reading an encoder gives at `counts` (turns * REN + angle, floor division).
[[nodiscard]] constexpr EncoderReading encoder_reading_at(int64_t counts) {
  const int64_t turns = counts >= 0 ? counts / kEncoderCounts : -((-counts + kEncoderCounts - 1) / kEncoderCounts);
  return {static_cast<int32_t>(turns), static_cast<uint16_t>(counts - turns * kEncoderCounts), 1};
}

[[nodiscard]] constexpr State initial_state(const StartPosition& p) {
  State s{};
  s.pos = p.pos;
  s.target = p.pos;
  s.homed = p.error == Error::None ? p.homed : uint8_t{0};
  return s;
}

}  // namespace ap::xy_axis
