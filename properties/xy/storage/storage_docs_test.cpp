// docs/storage.md carries the address map as a table; this keeps it equal to kItemMap.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <iterator>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/xy/storage/fram_map.hpp"

using namespace ap::xy_storage;

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string c;
  std::getline(ss, c, '|');  // text before the first bar
  while (std::getline(ss, c, '|')) out.push_back(trim(c));
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

std::string hex4(std::uint32_t v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", v);
  return buf;
}

const char* type_name(FieldType t) {
  switch (t) {
    case FieldType::U8: return "u8";
    case FieldType::I8: return "i8";
    case FieldType::U16: return "u16";
    case FieldType::U32: return "u32";
    case FieldType::I32: return "i32";
  }
  return "?";
}

const char* role_name(Role r) {
  switch (r) {
    case Role::Factory: return "factory";
    case Role::User: return "user";
    case Role::Reserved: return "reserved";
    case Role::StepCounter: return "step counter";
    case Role::Meta: return "meta";
  }
  return "?";
}

}  // namespace

// Rows: | id | name | A | B | bytes | type | role | default | min | max | unit |
TEST(storage_docs, map_table_matches_the_constexpr_map) {
  std::ifstream in(std::string(AP_SOURCE_DIR) + "/docs/storage.md");
  ASSERT_TRUE(in.good()) << "docs/storage.md missing";
  // Read through rdbuf(), not istreambuf_iterator: gcc 12 -O2 reports a false
  // -Wnull-dereference inside libstdc++'s istreambuf_iterator (the release preset's -Werror).
  std::stringstream whole;
  whole << in.rdbuf();
  const std::string text = whole.str();
  EXPECT_NE(text.find(std::string(kChip.part)), std::string::npos) << "the doc must name the part";

  std::map<std::string, std::vector<std::string>> rows;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) {
    const auto c = cells(line);
    if (c.size() == 11 && c[2].rfind("0x", 0) == 0) rows[c[1]] = c;
  }
  EXPECT_EQ(rows.size(), kItemCount);
  for (const MapEntry& e : kItemMap) {
    const std::string name(e.name);
    ASSERT_TRUE(rows.count(name)) << name << " missing from the doc table";
    const auto& c = rows[name];
    EXPECT_EQ(c[0], std::to_string(static_cast<int>(e.id))) << name;
    EXPECT_EQ(c[2], hex4(kCopyBase[0] + e.offset)) << name;
    EXPECT_EQ(c[3], hex4(kCopyBase[1] + e.offset)) << name;
    EXPECT_EQ(c[4], std::to_string(e.length)) << name;
    EXPECT_EQ(c[5], type_name(e.type)) << name;
    EXPECT_EQ(c[6], role_name(e.role) + std::string(e.rule == Rule::PowerOfTwo ? ", 2^n" : "")) << name;
    EXPECT_EQ(c[7], std::to_string(e.def)) << name;
    EXPECT_EQ(c[8], std::to_string(e.min)) << name;
    EXPECT_EQ(c[9], std::to_string(e.max)) << name;
    EXPECT_EQ(c[10], std::string(e.unit)) << name;
  }
}
