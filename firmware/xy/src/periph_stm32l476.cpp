// The peripheral layer of the thesis's board, an STM32L476RG (seed-000.md §1), at register
// level: no HAL, no vendor headers, no heap, no floating point. Every register address and bit
// below names the RM0351 (STM32L4x5/L4x6 reference manual) section it comes from, so it can be
// checked against the manual line by line; that check and ci/m4-build's link and size are all
// this file has had. QEMU has no STM32L4 machine, so none of it has run (docs/qemu.md "The
// STM32L476 image").
// One file, longer than the others: it is one table in code form, the registers of each
// peripheral in RM0351's order, read against the manual section by section.
#include <cstddef>
#include <cstdint>

#include "core/xy/axis/step_timer.hpp"
#include "firmware/xy/link_ring.hpp"
#include "firmware/xy/periph.hpp"

extern "C" void SysTick_Handler();
extern "C" void USART1_IRQHandler();
extern "C" void TIM2_IRQHandler();
extern "C" void TIM3_IRQHandler();

namespace ap::xy_fw {
namespace {

// ---------------------------------------------------------------------------------------------
// Pin map. The thesis gives none: it says only which signals reach MCU pins (TMC2130 CS, DIR,
// STEP; the encoders' and FRAM's chip selects) and which sit on the SPI GPIO expander (ENA, the
// BLE STATUS pins; seed-000.md §1 and §4.14). This map is ours, picked from the STM32L476RG
// LQFP64 alternate-function table so that no pin serves two functions, and must be replaced by
// the board's schematic before the image drives real hardware:
//   USART1 (BLE module)  PA9 TX, PA10 RX                  AF7
//   SPI1                 PA5 SCK, PA6 MISO, PA7 MOSI      AF5
//   I2C1 (TMP117, IMU)   PB8 SCL, PB9 SDA, open drain      AF4 (the board's pull-ups)
//   STEP X / STEP Y      PA0 TIM2_CH1 AF1, PC6 TIM3_CH1 AF2
//   DIR X / DIR Y        PB0, PB1                          outputs
//   ADC1                 PC0 ADC1_IN1 battery divider, PC1 ADC1_IN2 charge current sense
//   chip selects         the table kSpi below
struct Gpio {
  std::uint8_t port;  // 0 = GPIOA, 1 = GPIOB, 2 = GPIOC
  std::uint8_t pin;
};
constexpr Gpio pa(std::uint8_t n) { return {0, n}; }
constexpr Gpio pb(std::uint8_t n) { return {1, n}; }
constexpr Gpio pc(std::uint8_t n) { return {2, n}; }

// One SPI device: its chip select and the bus settings it needs; the bus is re-set between
// devices that differ.
struct SpiSlave {
  Gpio cs;
  std::uint8_t mode;      // CPOL << 1 | CPHA
  std::uint8_t br;        // SPI_CR1.BR: f_SCK = 80 MHz / 2^(br + 1)
  std::uint8_t setup_us;  // chip select low -> first clock edge
};
// TMC2130: mode 3 and at most 4 MHz on its internal clock (datasheet, "SPI interface"): 2.5 MHz.
// FRAM (MB85RS, the simulated part) and MCP23S17 expander: mode 0 or 3 (both datasheets), so 3
// like the drivers, which spares a bus re-set; 5 MHz is well inside both (33 and 10 MHz).
// RLS Orbis: the encoder shifts data out on the rising edge with the clock idle low, i.e. mode 1
// (the Orbis datasheet BRD01; the thesis says only "SPI"), at most 4 MHz: 1.25 MHz. It needs
// time after its select to latch the position (2.5 us single-turn, more with the multi-turn
// counter; 8 us covers both).
constexpr SpiSlave kSpi[xy_cosim::kSpiDevices] = {
    /* TmcX     */ {pb(12), 3, 4, 1},
    /* TmcY     */ {pb(13), 3, 4, 1},
    /* Fram     */ {pb(14), 3, 3, 1},
    /* EncoderX */ {pb(15), 1, 5, 8},
    /* EncoderY */ {pc(8), 1, 5, 8},
    /* Expander */ {pc(9), 3, 3, 1},
};
constexpr Gpio kDir[2] = {pb(0), pb(1)};
constexpr Gpio kKillSwitch = pb(2), kChargerEnable = pb(3);
constexpr Gpio kStep[2] = {pa(0), pc(6)};
constexpr std::uint32_t kStepAf[2] = {1, 2};
constexpr Gpio kUsartTx = pa(9), kUsartRx = pa(10);
constexpr Gpio kSpiSck = pa(5), kSpiMiso = pa(6), kSpiMosi = pa(7);
constexpr Gpio kI2cScl = pb(8), kI2cSda = pb(9);
constexpr Gpio kAdcPin[2] = {pc(0), pc(1)};
constexpr std::uint32_t kAdcInput[2] = {1, 2};  // ADC1_IN1, ADC1_IN2 (AdcChannel order)
// ---------------------------------------------------------------------------------------------

volatile std::uint32_t& reg(std::uintptr_t a) { return *reinterpret_cast<volatile std::uint32_t*>(a); }
volatile std::uint8_t& reg8(std::uintptr_t a) { return *reinterpret_cast<volatile std::uint8_t*>(a); }
// A read for its side effect only (a write's completion, a FIFO pop).
void touch(std::uintptr_t a) {
  const std::uint32_t v = reg(a);
  (void)v;
}
void touch8(std::uintptr_t a) {
  const std::uint8_t v = reg8(a);
  (void)v;
}

// Clock tree: MSI 4 MHz (its reset range) -> PLL (M 1, N 40, R 2: VCO 160 MHz) -> 80 MHz SYSCLK,
// AHB, APB1 and APB2 undivided. The step-timer maths (core/xy/axis step_timer.hpp, kTimerClockHz)
// assumes TIM2/TIM3 count 80 MHz: with APB1 undivided the timer clock is PCLK1 (RM0351 "Clock
// tree": x2 only when the APB prescaler is not 1). Without an LSE to trim MSI (MSIPLLEN) every
// rate is as accurate as MSI (datasheet: about 1 %), which the UART and step rates tolerate.
constexpr std::uint32_t kSysClkHz = 80'000'000;
static_assert(kSysClkHz == xy_axis::kTimerClockHz, "the step timer settings assume this timer clock");

// RM0351 "Reset and clock control (RCC)".
constexpr std::uintptr_t kRcc = 0x4002'1000;
constexpr std::uintptr_t kRccCr = kRcc + 0x00, kRccCfgr = kRcc + 0x08, kRccPllcfgr = kRcc + 0x0C;
constexpr std::uintptr_t kRccAhb2enr = kRcc + 0x4C, kRccApb1enr1 = kRcc + 0x58, kRccApb2enr = kRcc + 0x60;
constexpr std::uint32_t kCrMsirdy = 1U << 1, kCrPllon = 1U << 24, kCrPllrdy = 1U << 25;
constexpr std::uint32_t kCfgrSwPll = 3U << 0, kCfgrSwMask = 3U << 0, kCfgrSwsPll = 3U << 2, kCfgrSwsMask = 3U << 2;
// RCC_PLLCFGR: PLLSRC = MSI (01), PLLM = 1 (0), PLLN = 40, PLLR = 2 (00), PLLREN.
constexpr std::uint32_t kPllcfgr = (1U << 0) | (0U << 4) | (40U << 8) | (0U << 25) | (1U << 24);
constexpr std::uint32_t kAhb2GpioA = 1U << 0, kAhb2GpioB = 1U << 1, kAhb2GpioC = 1U << 2, kAhb2Adc = 1U << 13;
constexpr std::uint32_t kApb1Tim2 = 1U << 0, kApb1Tim3 = 1U << 1, kApb1I2c1 = 1U << 21, kApb1Pwr = 1U << 28;
constexpr std::uint32_t kApb2Spi1 = 1U << 12, kApb2Usart1 = 1U << 14;

// RM0351 "Embedded Flash memory (FLASH)", "Read access latency": 4 wait states above 64 MHz in
// range 1; prefetch and both caches on.
constexpr std::uintptr_t kFlashAcr = 0x4002'2000;
constexpr std::uint32_t kAcrLatency4 = 4U, kAcrLatencyMask = 7U, kAcrPrften = 1U << 8, kAcrIcen = 1U << 9,
                        kAcrDcen = 1U << 10;

// RM0351 "Power control (PWR)", "Dynamic voltage scaling management": range 1 (its reset value)
// is required above 26 MHz.
constexpr std::uintptr_t kPwrCr1 = 0x4000'7000, kPwrSr2 = 0x4000'7014;
constexpr std::uint32_t kCr1VosMask = 3U << 9, kCr1VosRange1 = 1U << 9, kSr2Vosf = 1U << 10;

// RM0351 "General-purpose I/Os (GPIO)", "GPIO registers".
constexpr std::uintptr_t kGpioA = 0x4800'0000, kGpioStride = 0x400;
constexpr std::uintptr_t kModer = 0x00, kOtyper = 0x04, kOspeedr = 0x08, kBsrr = 0x18, kAfrl = 0x20, kAfrh = 0x24;
// GPIOx_ASCR: on the STM32L47x the analog switch between a pin and the ADC is closed only here.
constexpr std::uintptr_t kAscr = 0x2C;
constexpr std::uint32_t kModeOut = 1, kModeAf = 2, kModeAnalog = 3;

// RM0351 "Universal synchronous asynchronous receiver transmitter (USART/UART)".
constexpr std::uintptr_t kUsart1 = 0x4001'3800;
constexpr std::uintptr_t kUsCr1 = 0x00, kUsBrr = 0x0C, kUsIsr = 0x1C, kUsIcr = 0x20, kUsRdr = 0x24, kUsTdr = 0x28;
constexpr std::uint32_t kUsCr1Ue = 1U << 0, kUsCr1Re = 1U << 2, kUsCr1Te = 1U << 3, kUsCr1Rxneie = 1U << 5;
constexpr std::uint32_t kUsIsrOre = 1U << 3, kUsIsrRxne = 1U << 5, kUsIsrTxe = 1U << 7;
constexpr std::uint32_t kUsIcrOrecf = 1U << 3;
// "USART baud rate generation", oversampling by 16: USARTDIV = f_CK / baud = 694.4 -> 694,
// 115 274 baud (+0.06 %). 8N1 is the reset framing (M = 00, STOP = 00, no parity).
constexpr std::uint32_t kUsartBrr = (kSysClkHz + 115'200 / 2) / 115'200;

// RM0351 "Serial peripheral interface (SPI)".
constexpr std::uintptr_t kSpi1 = 0x4001'3000;
constexpr std::uintptr_t kSpiCr1 = 0x00, kSpiCr2 = 0x04, kSpiSr = 0x08, kSpiDr = 0x0C;
constexpr std::uint32_t kSpiCr1Mstr = 1U << 2, kSpiCr1Spe = 1U << 6, kSpiCr1Ssi = 1U << 8, kSpiCr1Ssm = 1U << 9;
// 8-bit frames (DS = 0111) and RXNE at one byte in the receive FIFO (FRXTH), so that every byte
// written to DR as a byte answers with one byte read from DR as a byte ("Data packing").
constexpr std::uint32_t kSpiCr2Frame8 = (7U << 8) | (1U << 12);
constexpr std::uint32_t kSpiSrRxne = 1U << 0, kSpiSrTxe = 1U << 1, kSpiSrBsy = 1U << 7;

// RM0351 "Inter-integrated circuit (I2C) interface".
constexpr std::uintptr_t kI2c1 = 0x4000'5400;
constexpr std::uintptr_t kI2cCr1 = 0x00, kI2cCr2 = 0x04, kI2cTimingr = 0x10, kI2cIsr = 0x18, kI2cIcr = 0x1C,
                         kI2cRxdr = 0x24, kI2cTxdr = 0x28;
constexpr std::uint32_t kI2cCr1Pe = 1U << 0;
constexpr std::uint32_t kI2cCr2RdWrn = 1U << 10, kI2cCr2Start = 1U << 13, kI2cCr2Autoend = 1U << 25;
constexpr std::uint32_t kI2cIsrTxe = 1U << 0, kI2cIsrTxis = 1U << 1, kI2cIsrRxne = 1U << 2, kI2cIsrNackf = 1U << 4,
                        kI2cIsrStopf = 1U << 5, kI2cIsrTc = 1U << 6, kI2cIsrBerr = 1U << 8, kI2cIsrArlo = 1U << 9,
                        kI2cIsrBusy = 1U << 15;
constexpr std::uint32_t kI2cIcrAll = (1U << 3) | (1U << 4) | (1U << 5) | (1U << 8) | (1U << 9) | (1U << 10);
// "I2C timings" / I2C_TIMINGR for Fast-mode 400 kHz from I2CCLK = PCLK1 = 80 MHz, analog filter
// on: RM0351's example tables stop at 48 MHz, so this is ST's timing tool's value for 80 MHz,
// checked here against the manual's Fast-mode limits: PRESC 0 (12.5 ns), SCLL 145 (1.83 us
// >= t_LOW 1.3 us), SCLH 41 (0.53 us + sync and filter delays >= t_HIGH 0.6 us), SDADEL 0,
// SCLDEL 7 (100 ns >= t_SU;DAT 100 ns); about 2.5 us per bit with rise times.
constexpr std::uint32_t kI2cTiming400k = 0x0070'2991;

// RM0351 "General-purpose timers (TIM2/TIM3/TIM4/TIM5)".
constexpr std::uintptr_t kTim[2] = {0x4000'0000, 0x4000'0400};  // TIM2 (STEP X), TIM3 (STEP Y)
constexpr std::uintptr_t kTimCr1 = 0x00, kTimDier = 0x0C, kTimSr = 0x10, kTimEgr = 0x14, kTimCcmr1 = 0x18,
                         kTimCcer = 0x20, kTimCnt = 0x24, kTimPsc = 0x28, kTimArr = 0x2C, kTimCcr1 = 0x34;
constexpr std::uint32_t kTimCr1Cen = 1U << 0, kTimCr1Urs = 1U << 2, kTimCr1Opm = 1U << 3, kTimCr1Arpe = 1U << 7;
constexpr std::uint32_t kTimDierUie = 1U << 0, kTimSrUif = 1U << 0, kTimEgrUg = 1U << 0, kTimCcerCc1e = 1U << 0;
// Channel 1 in PWM mode 2 (OC1M = 0111: low while CNT < CCR1) with CCR1 preload: each period
// starts low, rises at CCR1 = (ARR + 1) / 2 and falls at the update. So DIR has half a period to
// settle before the first rising edge, and the update that ends a pulse comes before the next
// one begins, which is what lets the interrupt stop the train between two pulses.
constexpr std::uint32_t kCcmr1Pwm2 = (7U << 4) | (1U << 3);
constexpr std::uint32_t kCcmr1ForceLow = 4U << 4;  // OC1M = 0100: output held low

// RM0351 "Analog-to-digital converters (ADC)".
constexpr std::uintptr_t kAdc1 = 0x5004'0000, kAdcCommon = 0x5004'0300;
constexpr std::uintptr_t kAdcIsr = 0x00, kAdcCr = 0x08, kAdcCfgr = 0x0C, kAdcCfgr2 = 0x10, kAdcSmpr1 = 0x14,
                         kAdcSqr1 = 0x30, kAdcDr = 0x40, kAdcCcr = 0x08;
constexpr std::uint32_t kAdcIsrAdrdy = 1U << 0, kAdcIsrEoc = 1U << 2, kAdcIsrEos = 1U << 3, kAdcIsrOvr = 1U << 4;
constexpr std::uint32_t kAdcCrAden = 1U << 0, kAdcCrAdstart = 1U << 2, kAdcCrAdvregen = 1U << 28,
                        kAdcCrAdcal = 1U << 31;
// ADC_CR's set-only bits: written back as 0 (no effect) so that setting one never re-sets another.
constexpr std::uint32_t kAdcCrSetOnly = 0x8000'003FU;
// ADC_CFGR: its reset value (JQDIS) with OVRMOD; 12 bits, right aligned, single conversion,
// software trigger.
constexpr std::uint32_t kAdcCfgrSingle = (1U << 31) | (1U << 12);
// "Oversampler": regular oversampling (ROVSE), ratio x16 (OVSR = 011), shift 0 (OVSS = 0000):
// the sum of 16 twelve-bit samples, 0..65520, the 16-bit code firmware/xy/board_port.hpp converts.
constexpr std::uint32_t kAdcCfgr2Ovs16 = (1U << 0) | (3U << 2) | (0U << 5);
// Sample time 247.5 ADC clocks (SMP = 110) for the battery divider's source impedance: one
// oversampled conversion is 16 x 260 clocks = 52 us.
constexpr std::uint32_t kAdcSmp = 6U;
constexpr std::uint32_t kAdcCcrHclk1 = 1U << 16;  // CKMODE = 01: HCLK / 1, synchronous

// RM0351 "Independent watchdog (IWDG)": LSI 32 kHz / 4 = 8 kHz, reload 799: 100 ms (97..103 ms
// over the LSI's spread), a hundred control ticks.
constexpr std::uintptr_t kIwdg = 0x4000'3000;
constexpr std::uintptr_t kIwdgKr = kIwdg + 0x00, kIwdgPr = kIwdg + 0x04, kIwdgRlr = kIwdg + 0x08, kIwdgSr = kIwdg + 0x0C;
constexpr std::uint32_t kIwdgStart = 0xCCCC, kIwdgUnlock = 0x5555, kIwdgRefresh = 0xAAAA;
constexpr std::uint32_t kIwdgDiv4 = 0, kIwdgReload = 799;
// RM0351 "Debug support (DBG)", DBGMCU_APB1FZR1.DBG_IWDG_STOP: a core halted in the debugger
// halts the watchdog too.
constexpr std::uintptr_t kDbgmcuApb1fzr1 = 0xE004'2008;
constexpr std::uint32_t kDbgIwdgStop = 1U << 12;

// Cortex-M4 system control space (PM0214): SysTick, NVIC.
constexpr std::uintptr_t kSystCsr = 0xE000'E010, kSystRvr = 0xE000'E014, kSystCvr = 0xE000'E018;
constexpr std::uintptr_t kNvicIser = 0xE000'E100, kNvicIpr = 0xE000'E400, kShpr3SysTick = 0xE000'ED23;
constexpr std::uint32_t kIrqTim2 = 28, kIrqTim3 = 29, kIrqUsart1 = 37;

// Bounded waits count loop turns, not time: each turn (a peripheral read, a test, a taken
// branch) takes at least two core cycles, so `us` microseconds' worth of turns lasts at least
// that long, and ends even if the cycle count is off.
constexpr std::uint32_t kTurnsPerUs = kSysClkHz / 1'000'000 / 2;

template <class Ready>
bool wait_for(Ready ready, std::uint32_t us) {
  for (std::uint32_t i = us * kTurnsPerUs; i > 0; --i) {
    if (ready()) return true;
  }
  return ready();
}

void delay_us(std::uint32_t us) {
  for (std::uint32_t i = us * kTurnsPerUs; i > 0; --i) __asm volatile("");
}

std::uintptr_t gpio(Gpio g) { return kGpioA + kGpioStride * g.port; }

void gpio_set(Gpio g, bool high) { reg(gpio(g) + kBsrr) = high ? 1U << g.pin : 1U << (g.pin + 16U); }

void gpio_mode(Gpio g, std::uint32_t mode, std::uint32_t af = 0, bool open_drain = false) {
  const std::uintptr_t b = gpio(g);
  const std::uint32_t p = g.pin;
  reg(b + kOtyper) = (reg(b + kOtyper) & ~(1U << p)) | (open_drain ? 1U << p : 0U);
  reg(b + kOspeedr) = (reg(b + kOspeedr) & ~(3U << 2 * p)) | (2U << 2 * p);  // high speed
  const std::uintptr_t afr = b + (p < 8 ? kAfrl : kAfrh);
  const std::uint32_t s = (p % 8) * 4;
  reg(afr) = (reg(afr) & ~(0xFU << s)) | (af << s);
  reg(b + kModer) = (reg(b + kModer) & ~(3U << 2 * p)) | (mode << 2 * p);
}

void nvic_enable(std::uint32_t irq, std::uint8_t priority) {
  reg8(kNvicIpr + irq) = priority;
  reg(kNvicIser + 4 * (irq / 32)) = 1U << (irq % 32);
}

// The link's receive ring: 512 bytes, over 40 ms of the BLE module's 115200 baud, while thread
// mode empties it every 1 ms tick.
constinit LinkRing<512> ring;
volatile bool tick_pending = false;
// STEP pulses each axis's timer has still to emit; written by step_arm with the interrupt off.
volatile std::int32_t step_left[2] = {0, 0};
std::uint32_t spi_cr1 = 0;  // the SPI1 set-up in use (CR1 without SPE)
bool adc_ready = false;

void clocks() {
  reg(kRccApb1enr1) = reg(kRccApb1enr1) | kApb1Pwr;
  reg(kPwrCr1) = (reg(kPwrCr1) & ~kCr1VosMask) | kCr1VosRange1;
  const bool ok_vos = wait_for([] { return (reg(kPwrSr2) & kSr2Vosf) == 0; }, 1000);
  // Wait states before the faster clock ("Read access latency": increase first, then check).
  reg(kFlashAcr) = kAcrLatency4 | kAcrPrften | kAcrIcen | kAcrDcen;
  const bool ok_ws = wait_for([] { return (reg(kFlashAcr) & kAcrLatencyMask) == kAcrLatency4; }, 100);
  const bool ok_msi = wait_for([] { return (reg(kRccCr) & kCrMsirdy) != 0; }, 1000);
  reg(kRccPllcfgr) = kPllcfgr;
  reg(kRccCr) = reg(kRccCr) | kCrPllon;
  const bool ok_pll = wait_for([] { return (reg(kRccCr) & kCrPllrdy) != 0; }, 1000);
  // The record's pc field says which step failed: 0 before the switch, 1 the switch.
  if (!(ok_vos && ok_ws && ok_msi && ok_pll)) fault(xy_cosim::stop::kClock, 0, 0, 0, 0);
  // HPRE, PPRE1, PPRE2 keep their reset value /1.
  reg(kRccCfgr) = (reg(kRccCfgr) & ~kCfgrSwMask) | kCfgrSwPll;
  if (!wait_for([] { return (reg(kRccCfgr) & kCfgrSwsMask) == kCfgrSwsPll; }, 1000)) fault(xy_cosim::stop::kClock, 1, 0, 0, 0);
}

void usart_init() {
  gpio_mode(kUsartTx, kModeAf, 7);
  gpio_mode(kUsartRx, kModeAf, 7);
  reg(kUsart1 + kUsBrr) = kUsartBrr;
  reg(kUsart1 + kUsCr1) = kUsCr1Ue | kUsCr1Te | kUsCr1Re | kUsCr1Rxneie;
}

std::uint32_t spi_setting(const SpiSlave& s) {
  return kSpiCr1Mstr | kSpiCr1Ssm | kSpiCr1Ssi | (std::uint32_t{s.br} << 3) | s.mode;
}

// Clock polarity, phase and rate change only with SPE clear ("Configuration of SPI"); SPE is set
// again before the chip select falls, so the clock already idles at the new polarity.
void spi_use(const SpiSlave& s) {
  const std::uint32_t want = spi_setting(s);
  if (want == spi_cr1) return;
  (void)wait_for([] { return (reg(kSpi1 + kSpiSr) & kSpiSrBsy) == 0; }, 100);
  reg(kSpi1 + kSpiCr1) = want;
  reg(kSpi1 + kSpiCr1) = want | kSpiCr1Spe;
  spi_cr1 = want;
}

void spi_init() {
  for (const SpiSlave& s : kSpi) {
    gpio_set(s.cs, true);
    gpio_mode(s.cs, kModeOut);
  }
  gpio_mode(kSpiSck, kModeAf, 5);
  gpio_mode(kSpiMiso, kModeAf, 5);
  gpio_mode(kSpiMosi, kModeAf, 5);
  reg(kSpi1 + kSpiCr2) = kSpiCr2Frame8;
  spi_cr1 = 0;
  spi_use(kSpi[0]);
}

void i2c_reset() {
  // "Software reset": PE low for at least three APB clocks clears the state machine and flags.
  reg(kI2c1 + kI2cCr1) = 0;
  touch(kI2c1 + kI2cCr1);
  delay_us(1);
  reg(kI2c1 + kI2cCr1) = kI2cCr1Pe;
}

void i2c_init() {
  gpio_mode(kI2cScl, kModeAf, 4, true);
  gpio_mode(kI2cSda, kModeAf, 4, true);
  reg(kI2c1 + kI2cCr1) = 0;
  reg(kI2c1 + kI2cTimingr) = kI2cTiming400k;
  reg(kI2c1 + kI2cCr1) = kI2cCr1Pe;
}

void adc_set(std::uint32_t bit) { reg(kAdc1 + kAdcCr) = (reg(kAdc1 + kAdcCr) & ~kAdcCrSetOnly) | bit; }

// "ADC on-off control" and "Calibration": out of deep power-down, regulator on and settled,
// single-ended calibration, enable.
void adc_init() {
  for (std::size_t i = 0; i < 2; ++i) {
    gpio_mode(kAdcPin[i], kModeAnalog);
    reg(gpio(kAdcPin[i]) + kAscr) = reg(gpio(kAdcPin[i]) + kAscr) | 1U << kAdcPin[i].pin;
  }
  reg(kAdcCommon + kAdcCcr) = kAdcCcrHclk1;
  reg(kAdc1 + kAdcCr) = 0;  // DEEPPWD cleared
  reg(kAdc1 + kAdcCr) = kAdcCrAdvregen;
  delay_us(20);  // t_ADCVREG_STUP (datasheet: 20 us)
  adc_set(kAdcCrAdcal);
  if (!wait_for([] { return (reg(kAdc1 + kAdcCr) & kAdcCrAdcal) == 0; }, 1000)) return;
  delay_us(1);  // ADEN may not be set within 4 ADC clocks of the calibration's end
  reg(kAdc1 + kAdcIsr) = kAdcIsrAdrdy;
  adc_set(kAdcCrAden);
  if (!wait_for([] { return (reg(kAdc1 + kAdcIsr) & kAdcIsrAdrdy) != 0; }, 1000)) return;
  reg(kAdc1 + kAdcIsr) = kAdcIsrAdrdy;
  reg(kAdc1 + kAdcCfgr) = kAdcCfgrSingle;
  reg(kAdc1 + kAdcCfgr2) = kAdcCfgr2Ovs16;
  reg(kAdc1 + kAdcSmpr1) = kAdcSmp << (3 * kAdcInput[0]) | kAdcSmp << (3 * kAdcInput[1]);
  adc_ready = true;
}

void step_stop(std::size_t axis) {
  const std::uintptr_t t = kTim[axis];
  reg(t + kTimCr1) = kTimCr1Urs | kTimCr1Arpe;
  reg(t + kTimDier) = 0;
  reg(t + kTimSr) = 0;
  reg(t + kTimCcmr1) = kCcmr1ForceLow;
  step_left[axis] = 0;
}

void step_init() {
  // The supply held (KillSwitch low) and the charger connected until the core says otherwise.
  gpio_set(kKillSwitch, false);
  gpio_mode(kKillSwitch, kModeOut);
  gpio_set(kChargerEnable, true);
  gpio_mode(kChargerEnable, kModeOut);
  for (std::size_t a = 0; a < 2; ++a) {
    gpio_set(kDir[a], false);
    gpio_mode(kDir[a], kModeOut);
    const std::uintptr_t t = kTim[a];
    step_stop(a);
    reg(t + kTimCcer) = kTimCcerCc1e;  // active high
    gpio_mode(kStep[a], kModeAf, kStepAf[a]);
  }
}

void iwdg_start() {
  reg(kDbgmcuApb1fzr1) = reg(kDbgmcuApb1fzr1) | kDbgIwdgStop;
  reg(kIwdgKr) = kIwdgStart;
  reg(kIwdgKr) = kIwdgUnlock;
  reg(kIwdgPr) = kIwdgDiv4;
  reg(kIwdgRlr) = kIwdgReload;
  // The new values reach the LSI domain a few LSI clocks later; until then the reset values
  // (512 ms) apply, so a timeout here costs nothing but a longer first period.
  (void)wait_for([] { return reg(kIwdgSr) == 0; }, 1000);
  reg(kIwdgKr) = kIwdgRefresh;
}

// The step interrupt: one per pulse, at the update that ends it.
void step_isr(std::size_t axis) {
  const std::uintptr_t t = kTim[axis];
  if ((reg(t + kTimSr) & kTimSrUif) == 0) return;
  reg(t + kTimSr) = ~kTimSrUif;
  const std::int32_t left = step_left[axis] - 1;
  step_left[axis] = left;
  if (left == 1) {
    // One-pulse mode stops the counter at the next update, the end of the last pulse; the
    // interrupt needs only to come within this pulse's period.
    reg(t + kTimCr1) = reg(t + kTimCr1) | kTimCr1Opm;
  } else if (left <= 0) {
    reg(t + kTimDier) = 0;
    reg(t + kTimCcmr1) = kCcmr1ForceLow;
  }
}

// The fault record for the next boot: kept in .noinit, so neither the reset handler's .bss
// clearing nor the stack paint touches it; a debugger finds it by name.
constexpr std::uint32_t kFaultMagic = 0x4641'4C54;  // "FALT"
constexpr std::size_t kFaultWords = 7;              // magic, exception, pc, lr, cfsr, hfsr, check

}  // namespace

}  // namespace ap::xy_fw

// magic, exception, pc, lr, cfsr, hfsr, ~(xor of the six): valid when the check matches.
extern "C" {
[[gnu::section(".noinit"), gnu::used]] volatile std::uint32_t ap_fault_record[ap::xy_fw::kFaultWords];
}

namespace ap::xy_fw {

void periph_init() {
  clocks();
  reg(kRccAhb2enr) = reg(kRccAhb2enr) | kAhb2GpioA | kAhb2GpioB | kAhb2GpioC | kAhb2Adc;
  reg(kRccApb1enr1) = reg(kRccApb1enr1) | kApb1Tim2 | kApb1Tim3 | kApb1I2c1;
  reg(kRccApb2enr) = reg(kRccApb2enr) | kApb2Spi1 | kApb2Usart1;
  touch(kRccApb2enr);  // the enable reaches the peripherals before the first access to them
  step_init();
  spi_init();
  i2c_init();
  adc_init();
  usart_init();
  // A late step interrupt emits an extra pulse; a late receive interrupt loses a byte only
  // after a whole character time (87 us); SysTick only raises a flag.
  nvic_enable(kIrqTim2, 0x00);
  nvic_enable(kIrqTim3, 0x00);
  nvic_enable(kIrqUsart1, 0x40);
  reg8(kShpr3SysTick) = 0x80;
  reg(kSystRvr) = kSysClkHz / 1000 - 1;
  reg(kSystCvr) = 0;
  reg(kSystCsr) = 0x7;  // processor clock, interrupt, enable
  iwdg_start();
}

bool spi_transfer(SpiDevice dev, const std::uint8_t* tx, std::uint8_t* rx, std::size_t n) {
  const auto i = static_cast<std::size_t>(dev);
  if (i >= xy_cosim::kSpiDevices || n == 0) return false;
  const SpiSlave& s = kSpi[i];
  spi_use(s);
  gpio_set(s.cs, false);
  delay_us(s.setup_us);
  bool ok = true;
  // One byte in flight at a time: the bus is at most 5 MHz, so a byte (1.6 us) costs little
  // more than the loop, and the receive FIFO can never overrun.
  for (std::size_t k = 0; k < n && ok; ++k) {
    ok = wait_for([] { return (reg(kSpi1 + kSpiSr) & kSpiSrTxe) != 0; }, 50);
    if (!ok) break;
    reg8(kSpi1 + kSpiDr) = tx[k];
    ok = wait_for([] { return (reg(kSpi1 + kSpiSr) & kSpiSrRxne) != 0; }, 50);
    if (ok) rx[k] = reg8(kSpi1 + kSpiDr);
  }
  (void)wait_for([] { return (reg(kSpi1 + kSpiSr) & kSpiSrBsy) == 0; }, 50);
  gpio_set(s.cs, true);
  // A stuck transfer leaves bytes behind that would shift the next device's answer.
  for (int k = 0; k < 4 && (reg(kSpi1 + kSpiSr) & kSpiSrRxne) != 0; ++k) touch8(kSpi1 + kSpiDr);
  return ok;
}

xy_i2c::Status i2c_transfer(std::uint8_t addr7, const std::uint8_t* wr, std::size_t nw, std::uint8_t* rd, std::size_t nr) {
  // NBYTES is 8 bits and this driver does not reload: one phase moves at most 255 bytes.
  if (addr7 > 0x7F || nw > 255 || nr > 255) return xy_i2c::Status::BusError;
  constexpr std::uint32_t kByteUs = 1000;  // a byte is 23 us; the rest is a slave's clock stretch
  const std::uint32_t sadd = std::uint32_t{addr7} << 1;
  if (!wait_for([] { return (reg(kI2c1 + kI2cIsr) & kI2cIsrBusy) == 0; }, kByteUs)) {
    i2c_reset();
    return xy_i2c::Status::BusError;
  }
  reg(kI2c1 + kI2cIcr) = kI2cIcrAll;
  // Bytes of this phase the slave took: a NACK before the first is on the address.
  std::size_t sent = 0;
  auto failed = [] { return (reg(kI2c1 + kI2cIsr) & (kI2cIsrNackf | kI2cIsrBerr | kI2cIsrArlo)) != 0; };
  // The end of a transfer that did not complete: a NACK makes the master send STOP itself
  // ("Master transmitter"); a bus error, lost arbitration or timeout resets the peripheral.
  auto abort = [&sent] {
    const bool nack = (reg(kI2c1 + kI2cIsr) & kI2cIsrNackf) != 0;
    bool stopped = nack && wait_for([] { return (reg(kI2c1 + kI2cIsr) & kI2cIsrStopf) != 0; }, 1000);
    if (!stopped) i2c_reset();
    reg(kI2c1 + kI2cIcr) = kI2cIcrAll;
    reg(kI2c1 + kI2cIsr) = kI2cIsrTxe;  // flush a byte left in TXDR
    if (!nack) return xy_i2c::Status::BusError;
    return sent == 0 ? xy_i2c::Status::AddressNack : xy_i2c::Status::DataNack;
  };
  // The write phase (an address-only probe when both lengths are 0); without a read it ends
  // with STOP (AUTOEND), with one it ends at TC and the read phase's START is a repeated start.
  if (nw > 0 || nr == 0) {
    reg(kI2c1 + kI2cCr2) = sadd | static_cast<std::uint32_t>(nw) << 16 | kI2cCr2Start | (nr == 0 ? kI2cCr2Autoend : 0U);
    for (std::size_t i = 0; i < nw; ++i) {
      if (!wait_for([&] { return failed() || (reg(kI2c1 + kI2cIsr) & kI2cIsrTxis) != 0; }, kByteUs) || failed()) {
        return abort();
      }
      reg(kI2c1 + kI2cTxdr) = wr[i];
      ++sent;
    }
    const std::uint32_t done = nr == 0 ? kI2cIsrStopf : kI2cIsrTc;
    if (!wait_for([&] { return failed() || (reg(kI2c1 + kI2cIsr) & done) != 0; }, kByteUs) || failed()) {
      return abort();
    }
  }
  if (nr > 0) {
    sent = 0;  // a NACK now is on the address of the read
    reg(kI2c1 + kI2cCr2) =
        sadd | kI2cCr2RdWrn | static_cast<std::uint32_t>(nr) << 16 | kI2cCr2Start | kI2cCr2Autoend;
    for (std::size_t i = 0; i < nr; ++i) {
      if (!wait_for([&] { return failed() || (reg(kI2c1 + kI2cIsr) & kI2cIsrRxne) != 0; }, kByteUs) || failed()) {
        return abort();
      }
      rd[i] = static_cast<std::uint8_t>(reg(kI2c1 + kI2cRxdr));
    }
    if (!wait_for([] { return (reg(kI2c1 + kI2cIsr) & kI2cIsrStopf) != 0; }, kByteUs)) return abort();
  }
  reg(kI2c1 + kI2cIcr) = kI2cIcrAll;
  return xy_i2c::Status::Ok;
}

std::uint16_t adc_read(AdcChannel ch) {
  const auto i = static_cast<std::size_t>(ch);
  // A converter that never came up, or a conversion that never ends, reads as 0: an empty
  // battery, the reading on which the core stops rather than moves.
  if (!adc_ready || i >= 2) return 0;
  reg(kAdc1 + kAdcSqr1) = kAdcInput[i] << 6;  // L = 0: one conversion, SQ1 = the input
  reg(kAdc1 + kAdcIsr) = kAdcIsrEoc | kAdcIsrEos | kAdcIsrOvr;
  adc_set(kAdcCrAdstart);
  if (!wait_for([] { return (reg(kAdc1 + kAdcIsr) & kAdcIsrEoc) != 0; }, 500)) return 0;
  return static_cast<std::uint16_t>(reg(kAdc1 + kAdcDr));
}

void pin_write(Pin pin, bool level) {
  // ENA and the BLE status lines are on the GPIO expander (seed-000.md §1), driven through
  // spi_transfer by the board port; DIR, the KillSwitch and the charger enable are MCU pins.
  if (pin == Pin::DirX) gpio_set(kDir[0], level);
  if (pin == Pin::DirY) gpio_set(kDir[1], level);
  if (pin == Pin::KillSwitch) gpio_set(kKillSwitch, level);
  if (pin == Pin::ChargerEnable) gpio_set(kChargerEnable, level);
}

// The pulse train is counted by the update interrupt, one per pulse (the thesis's choice, seed
// gap G9). That bounds the rate: at 80 MHz an interrupt costs some 40 cycles, so both axes
// together are safe to a few hundred kHz, not to kStepFreqMax; a faster train would need a
// hardware count (TIM1/TIM8's repetition counter, or a slave timer clocked by STEP). A train
// still running when the next tick arms the timer is cut at that point.
void step_arm(std::size_t axis, std::uint16_t psc, std::uint16_t arr, std::int32_t steps) {
  if (axis >= 2) return;
  step_stop(axis);
  if (steps <= 0 || arr == 0) return;
  const std::uintptr_t t = kTim[axis];
  reg(t + kTimPsc) = psc;
  reg(t + kTimArr) = arr;
  reg(t + kTimCcr1) = xy_axis::step_ccr(xy_axis::TimerSetting{psc, arr});
  reg(t + kTimCnt) = 0;
  reg(t + kTimEgr) = kTimEgrUg;  // loads the preloaded PSC, ARR, CCR1; URS keeps UIF clear
  reg(t + kTimSr) = 0;
  step_left[axis] = steps;
  reg(t + kTimCcmr1) = kCcmr1Pwm2;
  reg(t + kTimDier) = kTimDierUie;
  reg(t + kTimCr1) = kTimCr1Urs | kTimCr1Arpe | (steps == 1 ? kTimCr1Opm : 0U) | kTimCr1Cen;
}

void link_send(const std::uint8_t* bytes, std::size_t n) {
  // Unbounded by design: a transmitter that never empties is a dead chip, and the watchdog
  // resets it.
  for (std::size_t i = 0; i < n; ++i) {
    while ((reg(kUsart1 + kUsIsr) & kUsIsrTxe) == 0) {
    }
    reg(kUsart1 + kUsTdr) = bytes[i];
  }
}

std::size_t link_take(std::uint8_t* out, std::size_t cap) { return ring.take(out, cap); }

std::uint32_t link_received() { return ring.received(); }

bool tick_wait() {
  // Interrupts masked between the test and WFI, so a SysTick between them is not slept through
  // for a whole tick: WFI still wakes on the pending interrupt, which runs once they are unmasked.
  for (;;) {
    __asm volatile("cpsid i" ::: "memory");
    if (tick_pending) break;
    __asm volatile("wfi");
    __asm volatile("cpsie i" ::: "memory");
  }
  tick_pending = false;
  __asm volatile("cpsie i" ::: "memory");
  reg(kIwdgKr) = kIwdgRefresh;
  return true;
}

// The board has no host to mirror it tick by tick (QEMU's Done message is the co-simulation's
// lockstep check), and its run never ends, so there is nothing to send; the stack's high-water
// mark stays readable by a debugger (stack_used()).
void tick_done(std::uint32_t, std::uint16_t, std::int32_t, std::int32_t) {}

void report(std::uint32_t, std::uint32_t, std::uint32_t) {}

void fault(std::uint8_t exception, std::uint32_t pc, std::uint32_t lr, std::uint32_t cfsr, std::uint32_t hfsr) {
  __asm volatile("cpsid i" ::: "memory");
  // No more STEP edges: the core that counted them is gone.
  for (std::size_t a = 0; a < 2; ++a) step_stop(a);
  const std::uint32_t w[kFaultWords - 1] = {kFaultMagic, exception, pc, lr, cfsr, hfsr};
  std::uint32_t check = 0;
  for (std::size_t i = 0; i < kFaultWords - 1; ++i) {
    ap_fault_record[i] = w[i];
    check ^= w[i];
  }
  ap_fault_record[kFaultWords - 1] = ~check;
  // Starts the watchdog if the fault came before periph_init did (its reset timeout, 512 ms);
  // otherwise it is running already. Either way it is never refreshed again.
  reg(kIwdgKr) = kIwdgStart;
  for (;;) __asm volatile("wfi");
}

}  // namespace ap::xy_fw

extern "C" void SysTick_Handler() { ap::xy_fw::tick_pending = true; }

extern "C" void USART1_IRQHandler() {
  using namespace ap::xy_fw;
  while ((reg(kUsart1 + kUsIsr) & kUsIsrRxne) != 0) {
    // A full ring drops the byte; the link's framing resynchronises (docs/protocol.md).
    (void)ring.put(static_cast<std::uint8_t>(reg(kUsart1 + kUsRdr)));
  }
  // An overrun keeps the interrupt pending until cleared; the byte it cost is gone either way.
  if ((reg(kUsart1 + kUsIsr) & kUsIsrOre) != 0) reg(kUsart1 + kUsIcr) = kUsIcrOrecf;
}

extern "C" void TIM2_IRQHandler() { ap::xy_fw::step_isr(0); }

extern "C" void TIM3_IRQHandler() { ap::xy_fw::step_isr(1); }
