#pragma once
// Markdown tables rendered from the codec tables. docs/protocol.md carries these lines
// verbatim; properties/xy/protocol checks that it still does (`axisproof frame doc` prints them).
#include <string>

namespace ap::xy_client {

std::string command_table_md();
std::string status_table_md();
std::string subscriber_table_md();
std::string error_table_md();
std::string all_tables_md();

}  // namespace ap::xy_client
