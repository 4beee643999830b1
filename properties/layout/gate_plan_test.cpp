// The gate's shard plan (cli/gate_plan.hpp, docs/ci.md "Shards"): every part in exactly one
// shard, the longest shard within Graham's bound, balance by seconds and not by count, new parts
// at their stage's mean, and the digest naming the assignment. The expectations are the
// scheduling rule's own (longest first, to the least-loaded shard), not the code's constants.
#include "cli/gate_plan.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <map>
#include <utility>
#include <string>
#include <vector>

namespace {

using ap::cli::gate_stages::make_plan;
using ap::cli::gate_stages::parse_times;
using ap::cli::gate_stages::xml_unescape;
using ap::cli::gate_stages::PartTimes;
using Parts = std::map<std::string, std::vector<std::string>>;

// Random stages of random parts, each with a recorded time in tenths of a second.
struct Input {
  Parts parts;
  PartTimes times;
  int count = 1;
};

rc::Gen<Input> inputs() {
  return rc::gen::exec([] {
    Input in;
    const int stages = *rc::gen::inRange(1, 5);
    for (int s = 0; s < stages; ++s) {
      const std::string stage = "stage" + std::to_string(s);
      const int n = *rc::gen::inRange(0, 40);
      for (int k = 0; k < n; ++k) {
        const std::string name = "part" + std::to_string(k);
        in.parts[stage].push_back(name);
        in.times[stage][name] = *rc::gen::inRange(0, 3000) / 10.0;
      }
    }
    in.count = *rc::gen::inRange(1, 9);
    return in;
  });
}

RC_GTEST_PROP(GatePlan, EveryPartRunsInExactlyOneShard, ()) {
  const Input in = *inputs();
  const auto plan = make_plan(in.parts, in.times, in.count);
  std::size_t listed = 0;
  for (const auto& [stage, names] : in.parts) listed += names.size();
  RC_ASSERT(plan.parts.size() == listed);
  std::map<std::pair<std::string, std::string>, int> seen;
  for (const auto& p : plan.parts) {
    RC_ASSERT(p.shard >= 1);
    RC_ASSERT(p.shard <= in.count);
    ++seen[{p.stage, p.name}];
  }
  for (const auto& [stage, names] : in.parts) {
    for (const auto& n : names) {
      const auto key = std::make_pair(stage, n);
      RC_ASSERT(seen[key] == 1);
    }
  }
}

// Graham (1969): greedy longest-first keeps the longest shard within mean + longest part.
RC_GTEST_PROP(GatePlan, LongestShardWithinTheMeanPlusTheLongestPart, ()) {
  const Input in = *inputs();
  const auto plan = make_plan(in.parts, in.times, in.count);
  std::vector<double> load(static_cast<std::size_t>(in.count), 0.0);
  double total = 0, longest = 0;
  for (const auto& p : plan.parts) {
    load[static_cast<std::size_t>(p.shard - 1)] += p.seconds;
    total += p.seconds;
    longest = std::max(longest, p.seconds);
  }
  const double worst = *std::max_element(load.begin(), load.end());
  RC_ASSERT(worst <= total / in.count + longest + 1e-9);
}

RC_GTEST_PROP(GatePlan, TheSameInputsGiveTheSamePlanAndDigest, ()) {
  const Input in = *inputs();
  const auto a = make_plan(in.parts, in.times, in.count);
  const auto b = make_plan(in.parts, in.times, in.count);
  RC_ASSERT(a.digest == b.digest);
  RC_ASSERT(a.parts.size() == b.parts.size());
  for (std::size_t i = 0; i < a.parts.size(); ++i) RC_ASSERT(a.parts[i].shard == b.parts[i].shard);
}

// One 10 s part and ten 1 s parts on two shards: by seconds the long part is alone (10 s
// each); a split by count would give each shard five or six parts and one of them 15 s.
TEST(GatePlan, BalancesBySecondsNotByCount) {
  Parts parts;
  PartTimes times;
  parts["tests"].push_back("long");
  times["tests"]["long"] = 10.0;
  for (int k = 0; k < 10; ++k) {
    parts["tests"].push_back("short" + std::to_string(k));
    times["tests"]["short" + std::to_string(k)] = 1.0;
  }
  const auto plan = make_plan(parts, times, 2);
  int long_shard = 0;
  for (const auto& p : plan.parts) {
    if (p.name == "long") long_shard = p.shard;
  }
  int with_long = 0;
  double loads[2] = {0, 0};
  for (const auto& p : plan.parts) {
    with_long += p.shard == long_shard ? 1 : 0;
    loads[p.shard - 1] += p.seconds;
  }
  EXPECT_EQ(with_long, 1);
  EXPECT_DOUBLE_EQ(loads[0], 10.0);
  EXPECT_DOUBLE_EQ(loads[1], 10.0);
}

// A part with no recorded time (a new test) weighs its stage's mean of the listed parts; with no
// times at all, every part weighs 1 s and the plan balances by count.
TEST(GatePlan, NewPartsWeighTheirStagesMean) {
  Parts parts{{"mutation", {"a", "b", "new"}}};
  PartTimes times{{"mutation", {{"a", 2.0}, {"b", 4.0}, {"gone", 100.0}}}};
  const auto plan = make_plan(parts, times, 2);
  for (const auto& p : plan.parts) {
    if (p.name == "new") EXPECT_DOUBLE_EQ(p.seconds, 3.0);
  }
  const auto none = make_plan(parts, {}, 3);
  std::vector<int> per(3, 0);
  for (const auto& p : none.parts) {
    EXPECT_DOUBLE_EQ(p.seconds, 1.0);
    ++per[static_cast<std::size_t>(p.shard - 1)];
  }
  EXPECT_EQ(per, (std::vector<int>{1, 1, 1}));
}

TEST(GatePlan, TheDigestNamesTheAssignment) {
  Parts parts{{"tests", {"a", "b", "c", "d"}}};
  const PartTimes times{{"tests", {{"a", 1.0}, {"b", 2.0}, {"c", 3.0}, {"d", 4.0}}}};
  const auto two = make_plan(parts, times, 2);
  const auto three = make_plan(parts, times, 3);
  EXPECT_NE(two.digest, three.digest);
  PartTimes other = times;
  other["tests"]["a"] = 9.0;  // a moves to the other shard
  EXPECT_NE(make_plan(parts, other, 2).digest, two.digest);
}

TEST(GatePlan, TimesFileLinesThatDoNotParseAreSkipped) {
  const auto t = parse_times("# stage\tpart\tseconds\ntests\ta\t1.5\ntests\tb\tslow\ntests\tc\n\ntests\td\t-1\nfuzz\ttarget:x\t10\n");
  ASSERT_EQ(t.size(), 2U);
  EXPECT_EQ(t.at("tests").size(), 1U);
  EXPECT_DOUBLE_EQ(t.at("tests").at("a"), 1.5);
  EXPECT_DOUBLE_EQ(t.at("fuzz").at("target:x"), 10.0);
}

// The name ctest's JUnit gives a parameterised test, read back as ctest -N lists it.
TEST(GatePlan, JunitNamesReadAsCtestListsThem) {
  EXPECT_EQ(xml_unescape("SimScenario/Bundled.Passes/sensors  # GetParam() = &quot;sensors&quot;"),
            "SimScenario/Bundled.Passes/sensors  # GetParam() = \"sensors\"");
  EXPECT_EQ(xml_unescape("a &lt;b&gt; &amp; &apos;c&apos;"), "a <b> & 'c'");
  EXPECT_EQ(xml_unescape("&amp;quot;"), "&quot;");  // one pass
  EXPECT_EQ(xml_unescape("&nbsp; &"), "&nbsp; &");  // unknown or bare: kept
}

}  // namespace
