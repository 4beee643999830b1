// The peripheral layer of the QEMU image (docs/qemu.md): QEMU's netduinoplus2, an STM32F405.
// USART1 (the BLE link), SysTick and the step timers' registers are the emulated chip's; QEMU
// models no device behind SPI, I2C or the ADC and no GPIO at all, so those transactions cross
// the co-simulation channel (protocol/xy/cosim/wire.hpp, over semihosting) to the host's device models.
// The host also grants every control tick, which makes a run independent of wall-clock timing.
#include <cstddef>
#include <cstdint>

#include "firmware/xy/link_ring.hpp"
#include "firmware/xy/periph.hpp"
#include "protocol/xy/cosim/wire.hpp"

extern "C" void SysTick_Handler();
extern "C" void USART1_IRQHandler();

namespace ap::xy_fw {
namespace {

volatile std::uint32_t& reg(std::uintptr_t a) { return *reinterpret_cast<volatile std::uint32_t*>(a); }

// STM32F405 reference manual RM0090: USART SR/DR/BRR/CR1, TIM PSC/ARR/CR1, NVIC, SysTick.
constexpr std::uintptr_t kUsart1 = 0x4001'1000;
constexpr std::uintptr_t kSr = 0x00, kDr = 0x04, kBrr = 0x08, kCr1 = 0x0C;
constexpr std::uint32_t kSrRxne = 1U << 5, kSrTxe = 1U << 7;
constexpr std::uint32_t kCr1Ue = 1U << 13, kCr1Te = 1U << 3, kCr1Re = 1U << 2, kCr1Rxneie = 1U << 5;
constexpr std::uintptr_t kTim[2] = {0x4000'0000, 0x4000'0400};  // TIM2 (STEP X), TIM3 (STEP Y)
constexpr std::uintptr_t kTimCr1 = 0x00, kTimPsc = 0x28, kTimArr = 0x2C;
constexpr std::uintptr_t kNvicIser1 = 0xE000'E104;
constexpr std::uint32_t kUsart1Irq = 37;
constexpr std::uintptr_t kSystCsr = 0xE000'E010, kSystRvr = 0xE000'E014, kSystCvr = 0xE000'E018;
// netduinoplus2 runs the core at 168 MHz; SysTick counts the core clock.
constexpr std::uint32_t kCoreHz = 168'000'000;
constexpr std::uint32_t kTickHz = 1000;

// The link's receive ring: 512 bytes, > one tick's worth at 115200 baud.
constinit LinkRing<512> ring;
volatile bool tick_pending = false;

// ARM semihosting (BKPT 0xAB): QEMU runs the call in the emulated CPU's thread and returns
// when it is done, so a whole message moves per call. QEMU's USART model would move one byte
// per main-loop turn (measured: 0.06x real time for the channel's traffic), docs/qemu.md.
constexpr std::uint32_t kSysOpen = 0x01, kSysWrite = 0x05, kSysRead = 0x06;
constexpr std::uint32_t kModeRb = 1, kModeWb = 5;

std::int32_t semihost(std::uint32_t op, const void* args) {
  register std::uint32_t r0 __asm("r0") = op;
  register const void* r1 __asm("r1") = args;
  __asm volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return static_cast<std::int32_t>(r0);
}

std::int32_t to_host = -1;   // cosim.to-host, opened for writing
std::int32_t to_image = -1;  // cosim.to-image, opened for reading

// Messages without an answer wait here until the next request (or the end of the tick), so a
// tick costs the host a few round trips, not one per message.
std::uint8_t out_buf[1024];
std::size_t out_len = 0;

void flush() {
  std::size_t done = 0;
  while (done < out_len) {
    const std::uint32_t a[3] = {static_cast<std::uint32_t>(to_host), reinterpret_cast<std::uintptr_t>(out_buf + done),
                                static_cast<std::uint32_t>(out_len - done)};
    const std::int32_t left = semihost(kSysWrite, a);
    if (left < 0 || static_cast<std::size_t>(left) > out_len - done) for (;;) __asm volatile("wfi");
    done = out_len - static_cast<std::size_t>(left);
  }
  out_len = 0;
}

void read_exact(std::uint8_t* buf, std::size_t n) {
  std::size_t done = 0;
  while (done < n) {
    const std::uint32_t a[3] = {static_cast<std::uint32_t>(to_image), reinterpret_cast<std::uintptr_t>(buf + done),
                                static_cast<std::uint32_t>(n - done)};
    const std::int32_t left = semihost(kSysRead, a);
    // All n - done bytes unread means end of file: the host is gone.
    if (left < 0 || static_cast<std::size_t>(left) >= n - done) for (;;) __asm volatile("wfi");
    done = n - static_cast<std::size_t>(left);
  }
}

std::int32_t open_file(const char* name, std::uint32_t len, std::uint32_t mode) {
  const std::uint32_t a[3] = {reinterpret_cast<std::uintptr_t>(name), mode, len};
  return semihost(kSysOpen, a);
}

void send(xy_cosim::Kind kind, const std::uint8_t* payload, std::size_t n) {
  if (out_len + n + 2 > sizeof out_buf) flush();
  out_buf[out_len++] = static_cast<std::uint8_t>(kind);
  out_buf[out_len++] = static_cast<std::uint8_t>(n);
  for (std::size_t i = 0; i < n; ++i) out_buf[out_len++] = payload[i];
}

// Reads one host message into buf; returns its kind and length.
xy_cosim::Kind receive(std::uint8_t* buf, std::size_t& n) {
  flush();
  std::uint8_t head[2];
  read_exact(head, 2);
  n = head[1];
  read_exact(buf, n);
  return static_cast<xy_cosim::Kind>(head[0]);
}

// A request the host answers with one Reply of exactly `want` bytes; anything else is a broken
// channel, which stops the image (the host reports where).
void request(xy_cosim::Kind kind, const std::uint8_t* payload, std::size_t n, std::uint8_t* reply, std::size_t want) {
  send(kind, payload, n);
  std::uint8_t buf[xy_cosim::kMaxPayload];
  std::size_t got = 0;
  if (receive(buf, got) != xy_cosim::Kind::Reply || got != want) fault(xy_cosim::stop::kChannel, 0, 0, 0, 0);
  for (std::size_t i = 0; i < want; ++i) reply[i] = buf[i];
}

}  // namespace

void periph_init() {
  // QEMU's USART needs no clock or baud set-up; BRR holds the 115200 baud of the BLE module at
  // the 84 MHz APB2 clock anyway, as on the chip.
  reg(kUsart1 + kBrr) = 84'000'000 / 115'200;
  reg(kUsart1 + kCr1) = kCr1Ue | kCr1Te | kCr1Re | kCr1Rxneie;
  reg(kNvicIser1) = 1U << (kUsart1Irq - 32);
  reg(kSystRvr) = kCoreHz / kTickHz - 1;
  reg(kSystCvr) = 0;
  reg(kSystCsr) = 0x7;  // processor clock, interrupt, enable
  // The host made both FIFOs in QEMU's working directory before starting it.
  static constexpr char kToHost[] = "cosim.to-host";
  static constexpr char kToImage[] = "cosim.to-image";
  to_host = open_file(kToHost, sizeof kToHost - 1, kModeWb);
  to_image = open_file(kToImage, sizeof kToImage - 1, kModeRb);
  if (to_host < 0 || to_image < 0) for (;;) __asm volatile("wfi");
  const std::uint8_t hello[1] = {xy_cosim::kVersion};
  send(xy_cosim::Kind::Hello, hello, 1);
}

bool spi_transfer(SpiDevice dev, const std::uint8_t* tx, std::uint8_t* rx, std::size_t n) {
  if (n == 0 || n + 1 > xy_cosim::kMaxPayload) return false;
  std::uint8_t p[xy_cosim::kMaxPayload];
  p[0] = static_cast<std::uint8_t>(dev);
  for (std::size_t i = 0; i < n; ++i) p[1 + i] = tx[i];
  request(xy_cosim::Kind::Spi, p, n + 1, rx, n);
  return true;
}

xy_i2c::Status i2c_transfer(std::uint8_t addr7, const std::uint8_t* wr, std::size_t nw, std::uint8_t* rd, std::size_t nr) {
  if (nw + 2 > xy_cosim::kMaxPayload || nr + 1 > xy_cosim::kMaxPayload) return xy_i2c::Status::BusError;
  std::uint8_t p[xy_cosim::kMaxPayload];
  p[0] = addr7;
  p[1] = static_cast<std::uint8_t>(nr);
  for (std::size_t i = 0; i < nw; ++i) p[2 + i] = wr[i];
  std::uint8_t r[xy_cosim::kMaxPayload];
  request(xy_cosim::Kind::I2c, p, nw + 2, r, nr + 1);
  for (std::size_t i = 0; i < nr; ++i) rd[i] = r[1 + i];
  // The host's device models end the transaction as the bus would (protocol/xy/cosim/wire.hpp).
  return r[0] <= static_cast<std::uint8_t>(xy_i2c::Status::BusError) ? static_cast<xy_i2c::Status>(r[0]) : xy_i2c::Status::BusError;
}

std::uint16_t adc_read(AdcChannel ch) {
  const std::uint8_t p[1] = {static_cast<std::uint8_t>(ch)};
  std::uint8_t r[2] = {};
  request(xy_cosim::Kind::Adc, p, 1, r, 2);
  return xy_cosim::get_u16(r);
}

void pin_write(Pin pin, bool level) {
  const std::uint8_t p[2] = {static_cast<std::uint8_t>(pin), static_cast<std::uint8_t>(level ? 1 : 0)};
  send(xy_cosim::Kind::PinWrite, p, 2);
}

void step_arm(std::size_t axis, std::uint16_t psc, std::uint16_t arr, std::int32_t steps) {
  // The timer is programmed as on the board and its registers are read back for the host, which
  // turns them into STEP edges: a wrong prescaler or reload shows as a wrong step rate.
  const std::uintptr_t t = kTim[axis];
  reg(t + kTimCr1) = 0;
  reg(t + kTimPsc) = psc;
  reg(t + kTimArr) = arr;
  if (steps > 0) reg(t + kTimCr1) = 1;
  std::uint8_t p[9];
  p[0] = static_cast<std::uint8_t>(axis);
  xy_cosim::put_u16(p + 1, static_cast<std::uint16_t>(reg(t + kTimPsc)));
  xy_cosim::put_u16(p + 3, static_cast<std::uint16_t>(reg(t + kTimArr)));
  xy_cosim::put_u32(p + 5, static_cast<std::uint32_t>(steps));
  send(xy_cosim::Kind::Step, p, sizeof p);
}

void link_send(const std::uint8_t* bytes, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    while ((reg(kUsart1 + kSr) & kSrTxe) == 0) {
    }
    reg(kUsart1 + kDr) = bytes[i];
  }
}

std::size_t link_take(std::uint8_t* out, std::size_t cap) { return ring.take(out, cap); }

std::uint32_t link_received() { return ring.received(); }

bool tick_wait() {
  while (!tick_pending) __asm volatile("wfi");
  tick_pending = false;
  send(xy_cosim::Kind::Ready, nullptr, 0);
  std::uint8_t buf[xy_cosim::kMaxPayload];
  std::size_t n = 0;
  const xy_cosim::Kind k = receive(buf, n);
  if (k == xy_cosim::Kind::End) return false;
  if (k != xy_cosim::Kind::Grant || n != 8) fault(xy_cosim::stop::kChannel, 0, 0, 0, 0);
  // Every link byte the host sent before this grant is in before the tick runs.
  const std::uint32_t delivered = xy_cosim::get_u32(buf + 4);
  while (ring.received() != delivered) {
  }
  return true;
}

void tick_done(std::uint32_t tick, std::uint16_t tx_bytes, std::int32_t x_pos, std::int32_t y_pos) {
  std::uint8_t p[14];
  xy_cosim::put_u32(p, tick);
  xy_cosim::put_u16(p + 4, tx_bytes);
  xy_cosim::put_u32(p + 6, static_cast<std::uint32_t>(x_pos));
  xy_cosim::put_u32(p + 10, static_cast<std::uint32_t>(y_pos));
  send(xy_cosim::Kind::Done, p, sizeof p);
}

void report(std::uint32_t stack_used, std::uint32_t stack_size, std::uint32_t ticks) {
  std::uint8_t p[12];
  xy_cosim::put_u32(p, stack_used);
  xy_cosim::put_u32(p + 4, stack_size);
  xy_cosim::put_u32(p + 8, ticks);
  send(xy_cosim::Kind::Report, p, sizeof p);
  flush();
}

void fault(std::uint8_t exception, std::uint32_t pc, std::uint32_t lr, std::uint32_t cfsr, std::uint32_t hfsr) {
  std::uint8_t p[17];
  p[0] = exception;
  xy_cosim::put_u32(p + 1, pc);
  xy_cosim::put_u32(p + 5, lr);
  xy_cosim::put_u32(p + 9, cfsr);
  xy_cosim::put_u32(p + 13, hfsr);
  send(xy_cosim::Kind::Fault, p, sizeof p);
  flush();
  for (;;) __asm volatile("wfi");
}

}  // namespace ap::xy_fw

extern "C" void SysTick_Handler() { ap::xy_fw::tick_pending = true; }

extern "C" void USART1_IRQHandler() {
  using namespace ap::xy_fw;
  while ((reg(kUsart1 + kSr) & kSrRxne) != 0) {
    const auto b = static_cast<std::uint8_t>(reg(kUsart1 + kDr));
    // The ring holds more than the host ever sends between two ticks; a full ring would be a
    // host bug, and the byte count it grants would then never be reached.
    (void)ring.put(b);
  }
}
