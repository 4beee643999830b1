// The vocabulary of the XY scenario language (docs/scenarios.md), shared by its parser
// (scenario.cpp) and its printer (scenario_print.cpp) so that both read and write the same
// words: the units of "Lexical rules", the fault kinds and directions of "Header", the verbs of
// "Actions", the times of "Expectations", and the dialect of the shared kit's lines.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "sim/scenario_text.hpp"
#include "sim/xy/scenario.hpp"

namespace ap::sim::xy::scenario {

// docs/scenarios.md "Lexical rules": a string escapes only \" and \\; a word missing at the end
// of a line is named. The language's times, title and numbers are its own (scenario.cpp).
inline const text::Dialect kDialect = {.full_escapes = false, .name_at_end = true, .cut_blank_hash = false, .one_title = false, .time = {}};

struct UnitDef {
  std::string_view name;
  Dim dim;
  double factor;   // to the canonical unit
};

// A unit of the table in docs/scenarios.md, or nullptr.
const UnitDef* find_unit(std::string_view u);
// What an error says a dimension is ("a length (um, mm, ...)").
std::string_view dim_name(Dim d);
// The verb an action's words name ("goto", "set speed", "link cut", ...).
std::optional<Verb> verb_of(std::string_view words);

// Letters, digits, _ + - and . (a word value, a parameter or TMC field name).
bool is_word(std::string_view w);
// [a-z0-9_-]+ (a scenario's name, the NAME of param./fram./sub. subjects).
bool is_name(std::string_view w);

// Indexed by FaultKind, Direction and When.
inline constexpr std::array<std::string_view, 5> kFaults{"drop", "duplicate", "reorder", "corrupt", "delay"};
inline constexpr std::array<std::string_view, 3> kDirs{"both", "to_board", "to_pc"};
inline constexpr std::array<std::string_view, 5> kWhens{"at", "always", "from", "by", "end"};

}  // namespace ap::sim::xy::scenario
