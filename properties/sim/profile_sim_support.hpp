// What the profiles' end-to-end tests share (their properties/<profile>/sim): the
// bundled scenarios of a folder, files and texts, and the line of a parse error (the profiles'
// parsers throw the shared sim/scenario_text.hpp ParseError).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim/scenario_text.hpp"

namespace ap::sim::test {

// The names (without .scn) of the scenarios in `dir`, sorted.
inline std::vector<std::string> bundled(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() == ".scn") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// A bundled scenario's name as a test name: anything but letters and digits becomes '_'.
inline std::string test_name(const ::testing::TestParamInfo<std::string>& i) {
  std::string n = i.param;
  std::replace_if(n.begin(), n.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) == 0; }, '_');
  return n;
}

inline std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// Whether a line of `v` holds `what`.
inline bool says(const std::vector<std::string>& v, const std::string& what) {
  return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.find(what) != std::string::npos; });
}

// The line `parse(text, "bad.scn")` names in its error (its message in *what), 0 when it parses.
template <class Parse>
int error_line(Parse parse, const std::string& text, std::string* what = nullptr) {
  try {
    parse(text, "bad.scn");
  } catch (const text::ParseError& e) {
    if (what != nullptr) *what = e.what();
    return e.line();
  }
  return 0;
}

// A text the parser must refuse: the line its error names and a part of the message.
struct ErrorCase {
  std::string text;
  int line;
  const char* says;
};

// Each case's error names bad.scn, its line, and says what it should.
template <class Parse>
void expect_errors(Parse parse, const std::vector<ErrorCase>& cases) {
  for (const ErrorCase& c : cases) {
    std::string what;
    EXPECT_EQ(error_line(parse, c.text, &what), c.line) << c.text;
    EXPECT_NE(what.find("bad.scn:" + std::to_string(c.line) + ": "), std::string::npos) << what;
    EXPECT_NE(what.find(c.says), std::string::npos) << what;
  }
}

}  // namespace ap::sim::test
