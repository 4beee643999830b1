// The board's peripherals behind one interface (docs/qemu.md "Peripherals"). Two
// implementations link against the same board port and core objects:
//   periph_stm32l476.cpp  the thesis's board: USART1 (BLE module), SPI1 (two TMC2130, FRAM,
//                         two encoders, GPIO expander), TIM2/TIM3 (STEP X/Y), ADC1 (battery,
//                         charge current), I2C1 (TMP117, ICM-20789), GPIO (chip selects, DIR);
//   periph_qemu.cpp       QEMU's netduinoplus2: USART1 and the step timers are the emulated
//                         STM32F405 peripherals; SPI, I2C, ADC and pin transactions cross the
//                         co-simulation channel (USART2) to the host's device models, which
//                         also grants each control tick.
// Everything here runs in thread mode except uart_rx_isr(), the link's receive interrupt.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/xy/i2c/port.hpp"
#include "protocol/xy/cosim/wire.hpp"

namespace ap::xy_fw {

using xy_cosim::AdcChannel;
using xy_cosim::Pin;
using xy_cosim::SpiDevice;

void periph_init();

// One full-duplex transfer with the device's chip select held for all n bytes.
bool spi_transfer(SpiDevice dev, const std::uint8_t* tx, std::uint8_t* rx, std::size_t n);
// Write `nw` bytes, then (repeated start) read `nr`: one transaction as core/xy/i2c defines it,
// its end as an xy_i2c::Status (a NACK on the address, on a data byte, or a bus fault).
xy_i2c::Status i2c_transfer(std::uint8_t addr7, const std::uint8_t* wr, std::size_t nw, std::uint8_t* rd, std::size_t nr);
// One conversion, 16-bit (the ADC's 12 bits oversampled x16, docs/qemu.md "Inputs").
std::uint16_t adc_read(AdcChannel ch);
void pin_write(Pin pin, bool level);
// Arms an axis's step timer for the coming tick: `steps` pulses with the given prescaler and
// auto-reload (xy_axis::step_timer); steps == 0 stops it.
void step_arm(std::size_t axis, std::uint16_t psc, std::uint16_t arr, std::int32_t steps);

// The BLE link: bytes out (blocking), bytes in through the receive ring (filled by the ISR).
void link_send(const std::uint8_t* bytes, std::size_t n);
// Moves at most `cap` received bytes out of the receive ring; returns how many.
std::size_t link_take(std::uint8_t* out, std::size_t cap);
// Bytes the receive interrupt has taken since power-up (wraps at 2^32).
std::uint32_t link_received();

// Blocks until the next 1 ms control tick may run (SysTick; on QEMU also the host's grant and
// every link byte the host sent before it). Returns false when the host ended the run.
bool tick_wait();
// The tick's summary for the host (QEMU: the co-simulation Done message; the board: nothing).
void tick_done(std::uint32_t tick, std::uint16_t tx_bytes, std::int32_t x_pos, std::int32_t y_pos);
// End of a run: the stack's high-water mark (bytes never overwritten since reset are painted).
void report(std::uint32_t stack_used, std::uint32_t stack_size, std::uint32_t ticks);
// A fault: reports where, then stops (the board: waits for the watchdog).
[[noreturn]] void fault(std::uint8_t exception, std::uint32_t pc, std::uint32_t lr, std::uint32_t cfsr,
                        std::uint32_t hfsr);

}  // namespace ap::xy_fw
