# The 3-axis USB control unit (seed 001; docs/unit3.md). Its code is built for the Cortex-M4
# and sized against the ATmega2560's budget (docs/unit3.md "MCU").
ap_declare_profile(unit3
  TITLE "3-axis USB control unit"
  SEED "seed-001 (docs/unit3.md)"
  MCU "ATmega2560 (256 KB flash, 8 KB RAM)"
  FLASH_BUDGET 262144 RAM_BUDGET 8192
  STATE_SYMBOL ap_unit3_state_bytes STATE_OBJECT Unit)
