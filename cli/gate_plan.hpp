#pragma once
// The shard plan of the release gate (docs/ci.md "Shards"): the parts of the stages that can be
// split, each with the seconds the last recorded run gave it, dealt to N shards. A pure
// function of its inputs, so that every shard of one commit, listing the same parts from the
// same build and reading the same times file, computes the same plan alone (and the join can
// tell by the digest that they did). Property-tested in properties/layout/gate_plan_test.cpp.
#include <map>
#include <string>
#include <vector>

namespace ap::cli::gate_stages {

struct PlannedPart {
  std::string stage;  // stage id (cmd_gate.cpp's table)
  std::string name;
  double seconds = 0;  // from the times, or the stage's mean when the part is new (1 s with no times)
  int shard = 1;
};

struct Plan {
  std::vector<PlannedPart> parts;  // sorted by stage, name
  std::string times_file;          // what balanced it ("" when there was none)
  std::string digest;              // of (stage, name, shard) of every part: equal plans, equal digests
};

// stage -> part -> seconds.
using PartTimes = std::map<std::string, std::map<std::string, double>>;

// A times file's text: "stage TAB part TAB seconds" lines, # comments; a damaged line is
// skipped (it costs balance, never correctness: the part gets its stage's mean).
PartTimes parse_times(const std::string& text);

// Deals the parts to `count` shards (1..64): longest first, each to the shard with the least
// seconds so far (ties: the lower shard). The longest shard then stays within the longest part
// of the mean (Graham's bound for this greedy rule).
Plan make_plan(const std::map<std::string, std::vector<std::string>>& parts, const PartTimes& times, int count);

// A JUnit attribute's text as ctest -N names the part: ctest's JUnit writer escapes & < > " '
// (a parameterised gtest's name carries `# GetParam() = "..."`), the plan does not, and the
// join matches the two by name. One pass, left to right; an unknown entity stays as it is.
std::string xml_unescape(const std::string& text);

}  // namespace ap::cli::gate_stages
