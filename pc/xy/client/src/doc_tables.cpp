#include "pc/xy/client/doc_tables.hpp"

#include <sstream>

#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/errors.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::xy_client {

namespace c = ap::xy_codec;

namespace {
std::string range(c::Range r) { return std::to_string(r.min) + " .. " + std::to_string(r.max); }
std::string id2(std::size_t id) {
  std::string s(2, '0');  // built in place: gcc 12 -O3 warns (-Wrestrict) on "0" + to_string
  s[0] = static_cast<char>('0' + id / 10 % 10);
  s[1] = static_cast<char>('0' + id % 10);
  return s;
}
}  // namespace

std::string command_table_md() {
  std::ostringstream o;
  o << "| ID | key | scope | data | unit | range |\n|---|---|---|---|---|---|\n";
  for (const auto& e : c::kCommands) {
    o << "| " << id2(static_cast<std::size_t>(e.id)) << " | `" << e.key << "` | "
      << (e.scope == c::Scope::Unit ? "unit" : "axis") << " | " << e.meaning << " | " << e.unit << " | "
      << range(e.range) << " |\n";
  }
  return o.str();
}

std::string status_table_md() {
  std::ostringstream o;
  o << "| echo ID | key | status | data | unit | range |\n|---|---|---|---|---|---|\n";
  for (const auto& e : c::kStatuses) {
    o << "| " << id2(static_cast<std::size_t>(e.id)) << " | `" << e.key << "` | " << e.meaning << " | " << e.data
      << " | " << e.unit << " | " << range(e.range) << " |\n";
  }
  return o.str();
}

std::string subscriber_table_md() {
  std::ostringstream o;
  o << "| ID | key | value | argument | arg range | unit | data range |\n|---|---|---|---|---|---|---|\n";
  for (const auto& e : c::kSubscribers) {
    o << "| " << id2(static_cast<std::size_t>(e.id)) << " | `" << e.key << "` | " << e.meaning << " | " << e.arg
      << " | " << range(e.arg_range) << " | " << e.unit << " | " << range(e.range) << " |\n";
  }
  return o.str();
}

std::string error_table_md() {
  std::ostringstream o;
  o << "| code | key | meaning |\n|---|---|---|\n";
  for (const auto& e : c::kFrameErrors) {
    o << "| " << id2(static_cast<std::size_t>(e.error)) << " | `" << e.key << "` | " << e.meaning << " |\n";
  }
  return o.str();
}

std::string all_tables_md() {
  return "### Commands\n\n" + command_table_md() + "\n### Echo statuses\n\n" + status_table_md() +
         "\n### Subscribers\n\n" + subscriber_table_md() + "\n### Rejection reasons\n\n" + error_table_md();
}

}  // namespace ap::xy_client
