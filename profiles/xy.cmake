# The wireless XY positioning platform (seed 000) with the CNC paths of seed 003: the
# harness's default profile. Its folders are every <layer>/xy (docs/profiles.md).
ap_declare_profile(xy DEFAULT
  TITLE "wireless XY positioning platform"
  SEED "seed-000 (docs/architecture.md)"
  MCU "STM32L476, Cortex-M4F (1 MB flash, 128 KB RAM)"
  FLASH_BUDGET 1048576 RAM_BUDGET 131072
  STATE_SYMBOL ap_xy_state_bytes STATE_OBJECT Board
  SIZE_TAG m4
  USES core/intmath core/result)
