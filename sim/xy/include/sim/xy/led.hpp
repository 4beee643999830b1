// The telemetry's LED code in the words of the scenario language (`board.led`, docs/sim.md
// "Expectations"; the code of docs/sim.md "The simulated board": Tab. 7-4 colour and blink).
// A header of its own so that the PC side reads the code without the board's header
// (sim/xy/board.hpp).
#pragma once

#include <cstdint>
#include <string>

namespace ap::sim::xy {

std::string led_word(std::uint8_t code);   // "red_fast", "blue", ...

}  // namespace ap::sim::xy
