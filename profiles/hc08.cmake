# The HC08 single-motor unit (seed 002; docs/hc08.md). Debian's only HC08 compiler, SDCC,
# compiles C, not C++: the code is built for the Cortex-M4 and sized against the MC68HC908LJ12's
# budget (docs/hc08.md "MCU").
ap_declare_profile(hc08
  TITLE "HC08 single-motor unit"
  SEED "seed-002 (docs/hc08.md)"
  MCU "MC68HC908LJ12 (12 KB flash, 512 B RAM)"
  FLASH_BUDGET 12288 RAM_BUDGET 512
  STATE_SYMBOL ap_hc08_state_bytes STATE_OBJECT Board)
