// Reset and exception entry of both images (docs/qemu.md "Images"): the vector table, the C++
// run-time set-up (data, bss, FPU, constructors), the stack paint, and fault capture. The
// STM32L476 and the STM32F405 share the Cortex-M4 core exceptions and the interrupt numbers
// used here (USART1 37, TIM2 28, TIM3 29), so one table serves both.
#include <cstddef>
#include <cstdint>

#include "firmware/xy/app.hpp"
#include "firmware/xy/periph.hpp"
#include "firmware/xy/stack.hpp"
#include "protocol/xy/cosim/wire.hpp"

extern "C" {
extern std::uint32_t __stack_bottom[];
extern std::uint32_t __stack_top[];
extern std::uint32_t __handler_stack_bottom[];
extern std::uint32_t __handler_stack_top[];
extern std::uint32_t __data_start[];
extern std::uint32_t __data_end[];
extern const std::uint32_t __data_load[];
extern std::uint32_t __bss_start[];
extern std::uint32_t __bss_end[];
extern void (*const __init_array_start[])();
extern void (*const __init_array_end[])();

[[noreturn]] void Reset_Handler();
[[noreturn]] void reset_on_thread_stack();
void Fault_Handler();
void SysTick_Handler();
void USART1_IRQHandler();
// The step timers' pulse counters: the STM32L476 layer defines them; the QEMU layer never
// enables these interrupts, so there they stay what any unclaimed interrupt is, a fault.
[[gnu::weak, gnu::alias("Fault_Handler")]] void TIM2_IRQHandler() noexcept;
[[gnu::weak, gnu::alias("Fault_Handler")]] void TIM3_IRQHandler() noexcept;
}

namespace {

volatile std::uint32_t& reg(std::uintptr_t a) { return *reinterpret_cast<volatile std::uint32_t*>(a); }

constexpr std::uintptr_t kCpacr = 0xE000ED88;
constexpr std::uintptr_t kCfsr = 0xE000ED28;
constexpr std::uintptr_t kHfsr = 0xE000ED2C;
// Words kept unpainted below the reset handler's own frame while painting.
constexpr std::size_t kPaintMargin = 16;

}  // namespace

namespace ap::xy_fw {

std::uint32_t stack_size() {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(__stack_top) -
                                    reinterpret_cast<std::uintptr_t>(__stack_bottom));
}

std::uint32_t stack_used() {
  const std::uint32_t* p = __stack_bottom;
  while (p < __stack_top && *p == kStackPaint) ++p;
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(__stack_top) - reinterpret_cast<std::uintptr_t>(p));
}

bool stack_overflowed() { return __stack_bottom[0] != kStackPaint; }

bool handler_stack_overflowed() { return __handler_stack_bottom[0] != kStackPaint; }

}  // namespace ap::xy_fw

extern "C" {

// Thread mode moves to its own stack (PSP) before anything else runs; exceptions keep the one
// the vector table gives (MSP). A thread stack that runs off the bottom of RAM then faults on a
// push, and the fault handler still has a stack to report it from: with one stack for both,
// the fault's own entry faults again and the core locks up (QEMU then aborts with "Lockup", no
// address). Naked: nothing may touch the stack between the switch and the C++ that follows.
[[gnu::naked, noreturn]] void Reset_Handler() {
  __asm volatile(
      "movw r0, #:lower16:__stack_top\n"
      "movt r0, #:upper16:__stack_top\n"
      "msr psp, r0\n"
      "movs r0, #2\n"  // CONTROL.SPSEL: thread mode uses PSP
      "msr control, r0\n"
      "isb\n"
      "b reset_on_thread_stack\n");
}

[[noreturn]] void reset_on_thread_stack() {
  // Paint first, while nothing below this frame is in use: every word never written since
  // reset still holds the pattern at the end of a run. Nothing has run on the handler stack.
  std::uintptr_t sp = 0;
  __asm volatile("mov %0, sp" : "=r"(sp));
  const std::uintptr_t limit_addr = sp - kPaintMargin * sizeof(std::uint32_t);
  auto* limit = reinterpret_cast<std::uint32_t*>(limit_addr);
  for (std::uint32_t* p = __stack_bottom; p < limit; ++p) *p = ap::xy_fw::kStackPaint;
  for (std::uint32_t* p = __handler_stack_bottom; p < __handler_stack_top; ++p) *p = ap::xy_fw::kStackPaint;
  const std::uint32_t* src = __data_load;
  for (std::uint32_t* p = __data_start; p < __data_end; ++p) *p = *src++;
  for (std::uint32_t* p = __bss_start; p < __bss_end; ++p) *p = 0;
  // CP10 and CP11 full access: the core is built for the FPU's calling convention (hard float).
  reg(kCpacr) = reg(kCpacr) | (0xFU << 20);
  __asm volatile("dsb\n isb" ::: "memory");
  for (auto* f = __init_array_start; f < __init_array_end; ++f) (*f)();
  ap::xy_fw::run();
  for (;;) __asm volatile("wfi");  // the run ended: the host stops the machine
}

// The exception frame the core stacked: r0 r1 r2 r3 r12 lr pc xpsr. A frame that does not lie
// inside the stack it was pushed on was never written: the push that should have stacked it
// faulted (CFSR STKERR), because that stack had run out. The fault is then the overflow, and
// the stack pointer it left is its address.
[[noreturn]] void fault_frame(const std::uint32_t* frame, std::uint32_t exc_return) {
  std::uint32_t ipsr = 0;
  __asm volatile("mrs %0, ipsr" : "=r"(ipsr));
  const bool on_thread_stack = (exc_return & 4U) != 0;
  const std::uint32_t* lo = on_thread_stack ? __stack_bottom : __handler_stack_bottom;
  const std::uint32_t* hi = on_thread_stack ? __stack_top : __handler_stack_top;
  const auto at = [](const std::uint32_t* p) { return reinterpret_cast<std::uintptr_t>(p); };
  if (at(frame) < at(lo) || at(frame) + 8 * sizeof(std::uint32_t) > at(hi)) {
    ap::xy_fw::fault(ap::xy_cosim::stop::kStackRanOut, static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(frame)), exc_return,
                  reg(kCfsr), reg(kHfsr));
  }
  ap::xy_fw::fault(static_cast<std::uint8_t>(ipsr & 0xFFU), frame[6], frame[5], reg(kCfsr), reg(kHfsr));
}

// Hard, memory, bus and usage faults, NMI and every interrupt nobody claims: a fault, with the
// faulting instruction's address from the stacked frame of whichever stack was in use.
[[gnu::naked]] void Fault_Handler() {
  __asm volatile(
      "tst lr, #4\n"
      "ite eq\n"
      "mrseq r0, msp\n"
      "mrsne r0, psp\n"
      "mov r1, lr\n"
      "b fault_frame\n");
}

}  // extern "C"

namespace {

using Handler = void (*)();
union Vector {
  Handler handler;
  std::uint32_t* stack;
};

constexpr std::size_t kExternalIrqs = 82;  // STM32L476 and STM32F405 both end at IRQ 81

constexpr auto make_table() {
  struct Table {
    Vector v[16 + kExternalIrqs];
  } t{};
  for (auto& e : t.v) e.handler = &Fault_Handler;
  t.v[0].stack = __handler_stack_top;  // MSP; the reset handler gives thread mode __stack_top
  t.v[1].handler = &Reset_Handler;
  t.v[11].handler = &Fault_Handler;  // SVCall: unused, so unexpected
  t.v[15].handler = &SysTick_Handler;
  t.v[16 + 28].handler = &TIM2_IRQHandler;
  t.v[16 + 29].handler = &TIM3_IRQHandler;
  t.v[16 + 37].handler = &USART1_IRQHandler;
  return t;
}

}  // namespace

[[gnu::section(".isr_vector"), gnu::used]] constinit const auto kVectors = make_table();
