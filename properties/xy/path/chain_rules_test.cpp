// docs/cnc.md's chain rules checked from outside the path executor: random contours of lines and
// arcs (small arcs tangent to lines among them) are streamed into core/xy/path the way a PC does
// (one segment a tick, waiting for queue space on QueueFull, path_end last), and the
// independent checker models/xy/cnc_rules watches the submitted segments and the per-tick
// positions and axis speeds. Expectations are docs/cnc.md's ("Chains", "Speeds", "Refusals"),
// never the executor's code.
#include "models/xy/cnc_rules/chain_rules.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <ostream>
#include <string>
#include <vector>

#include "core/xy/path/executor.hpp"

namespace ap::model::xy_cnc_rules {
// RapidCheck's counterexamples print the contour.
inline void showValue(const Segment& s, std::ostream& os) {
  os << (s.kind == Kind::Line ? "line " : (s.kind == Kind::ArcCw ? "cw " : "ccw ")) << "(" << s.start[0] << ","
     << s.start[1] << ")->(" << s.end[0] << "," << s.end[1] << ")";
  if (s.kind != Kind::Line) os << " c(" << s.centre[0] << "," << s.centre[1] << ")";
}
}  // namespace ap::model::xy_cnc_rules

namespace ap::xy_path {
inline void showValue(const Limits& l, std::ostream& os) {
  os << "v " << l.motion.v_max << " a " << l.motion.a_max << " j " << l.motion.j_max;
}
}  // namespace ap::xy_path

namespace {

namespace cr = ap::model::xy_cnc_rules;
using ap::xy_path::Error;
using ap::xy_path::Executor;

ap::xy_path::Segment to_core(const cr::Segment& s) {
  const auto k = s.kind == cr::Kind::Line
                     ? ap::xy_path::Kind::Line
                     : (s.kind == cr::Kind::ArcCw ? ap::xy_path::Kind::ArcCw : ap::xy_path::Kind::ArcCcw);
  const auto p = [](const cr::Point& q) {
    return ap::xy_path::Point{static_cast<std::int32_t>(q[0]), static_cast<std::int32_t>(q[1])};
  };
  return {k, p(s.start), p(s.end), p(s.centre)};
}

ap::xy_path::Limits limits(std::int32_t v, std::int32_t a, std::int32_t j) {
  ap::xy_path::Limits l;
  l.motion = {v, a, j};
  l.soft_min = {-4000000, -4000000};
  l.soft_max = {4000000, 4000000};
  return l;
}

cr::Config config_of(const ap::xy_path::Limits& l) {
  cr::Config c;
  c.v_max = l.motion.v_max;
  c.a_max = l.motion.a_max;
  c.j_max = l.motion.j_max;
  return c;
}

struct Streamed {
  cr::ChainChecker chk;
  cr::Point pos{};
  std::size_t delivered = 0;
  std::string unexpected;  // a refusal other than QueueFull
  bool active = false;     // the executor still had a path when the run ended
};

// A PC streaming a contour: up to `burst` segments a tick, in order; on QueueFull it waits (the
// next tick it tries the same segment again); path_end only after the last segment. The board
// ticks after the PC's frames. Stops at the end of the path, on the checker's first violation,
// after max_ticks without path_end (the checker's live.space bounds every wait before it), or
// once the checker's live.end deadline has passed (the docs' time bound of the chains left).
Streamed stream(const std::vector<cr::Segment>& segs, const ap::xy_path::Limits& lim, std::size_t burst,
                std::uint64_t max_ticks = 400000) {
  Executor e;
  Streamed r{cr::ChainChecker(config_of(lim), segs.front().start), segs.front().start, 0, {}};
  ap::xy_path::Point pos{static_cast<std::int32_t>(r.pos[0]), static_cast<std::int32_t>(r.pos[1])};
  bool end_sent = false;
  for (std::uint64_t t = 0; end_sent ? r.chk.ticks() <= r.chk.end_deadline() : t < max_ticks; ++t) {
    for (std::size_t b = 0; b < burst && !end_sent; ++b) {
      if (r.delivered < segs.size()) {
        const Error err = e.add(to_core(segs[r.delivered]), lim);
        if (err == Error::None) {
          r.chk.accepted(segs[r.delivered]);
          ++r.delivered;
          continue;
        }
        if (err == Error::QueueFull) {
          r.chk.refused_queue_full();
        } else {
          r.unexpected =
              std::string("segment #") + std::to_string(r.delivered) + " refused: " + ap::xy_path::error_name(err);
        }
        break;
      }
      e.close();
      r.chk.path_end();
      end_sent = true;
    }
    if (!r.unexpected.empty()) break;
    ap::xy_path::Halt h = ap::xy_path::Halt::None;
    const ap::xy_path::TickOut o = e.tick({}, pos, h);
    r.chk.tick({pos[0], pos[1]}, {o.v_fine[0], o.v_fine[1]}, o.steps);
    if (!r.chk.ok()) break;
    if (end_sent && !e.active()) break;
  }
  r.pos = {pos[0], pos[1]};
  r.active = e.active();
  r.chk.finish();
  return r;
}

cr::Point primitive(cr::Point d) {
  const std::int64_t g = std::gcd(std::llabs(d[0]), std::llabs(d[1]));
  return g == 0 ? d : cr::Point{d[0] / g, d[1] / g};
}

// An arc leaving `at` in direction d (primitive), tangent to it: the centre lies m steps of d's
// normal to its left (ccw) or right (cw), so the start's tangent is exactly parallel to d
// (docs/cnc.md "Chains": integer cross product 0). It sweeps `deg` degrees; the end is the
// nearest step to the circle there.
cr::Segment tangent_arc(const cr::Point& at, const cr::Point& d, std::int64_t m, bool ccw, double deg) {
  const cr::Point n = ccw ? cr::Point{-d[1], d[0]} : cr::Point{d[1], -d[0]};
  const cr::Point c{at[0] + m * n[0], at[1] + m * n[1]};
  const double sx = static_cast<double>(at[0] - c[0]);
  const double sy = static_cast<double>(at[1] - c[1]);
  const double th = (ccw ? 1 : -1) * deg * M_PI / 180.0;
  const cr::Point e{c[0] + std::llround(sx * std::cos(th) - sy * std::sin(th)),
                    c[1] + std::llround(sx * std::sin(th) + sy * std::cos(th))};
  return {ccw ? cr::Kind::ArcCcw : cr::Kind::ArcCw, at, e, c};
}

cr::Segment line_along(const cr::Point& at, const cr::Point& d, std::int64_t k) {
  return {cr::Kind::Line, at, {at[0] + k * d[0], at[1] + k * d[1]}, {}};
}

// Random contours: lines of 1..max_len steps and arcs of radius 1..max_r steps, most junctions
// tangent (lines into arcs, arcs into lines and arcs), corner_percent of them corners.
rc::Gen<std::vector<cr::Segment>> gen_contour(int min_n, int max_n, int corner_percent, std::int64_t max_len,
                                              std::int64_t max_r) {
  return rc::gen::exec([=] {
    const int n = *rc::gen::inRange(min_n, max_n + 1);
    std::vector<cr::Segment> segs;
    cr::Point at{0, 0};
    cr::Point d{0, 0};
    while (d[0] == 0 && d[1] == 0) d = primitive({*rc::gen::inRange(-6, 7), *rc::gen::inRange(-6, 7)});
    for (int k = 0; k < n; ++k) {
      if (k > 0 && *rc::gen::inRange(0, 100) < corner_percent) {
        cr::Point nd{0, 0};
        while (nd[0] == 0 && nd[1] == 0) nd = primitive({*rc::gen::inRange(-6, 7), *rc::gen::inRange(-6, 7)});
        d = nd;
      }
      const double dlen = std::hypot(static_cast<double>(d[0]), static_cast<double>(d[1]));
      const std::int64_t dmax = std::max(std::llabs(d[0]), std::llabs(d[1]));
      cr::Segment s;
      if (*rc::gen::inRange(0, 2) == 0) {
        const std::int64_t len =
            *rc::gen::oneOf(rc::gen::inRange<std::int64_t>(1, 40), rc::gen::inRange<std::int64_t>(40, max_len));
        s = line_along(at, d, std::max<std::int64_t>(1, len / dmax));
      } else {
        // Radius m |d|: small arcs (a few steps) are the interesting ones at a join.
        const std::int64_t r =
            *rc::gen::oneOf(rc::gen::inRange<std::int64_t>(1, 12), rc::gen::inRange<std::int64_t>(12, max_r));
        const auto m = std::max<std::int64_t>(1, static_cast<std::int64_t>(static_cast<double>(r) / dlen));
        s = tangent_arc(at, d, m, *rc::gen::arbitrary<bool>(), *rc::gen::inRange(10, 361));
        if (s.end == s.start && s.kind != cr::Kind::Line && *rc::gen::inRange(0, 4) != 0) {
          s = tangent_arc(at, d, m, s.kind == cr::Kind::ArcCcw, 90);
        }
      }
      segs.push_back(s);
      at = s.end;
      const cr::Point x = cr::exit_direction(s);
      d = primitive(x);
    }
    return segs;
  });
}

rc::Gen<ap::xy_path::Limits> gen_limits() {
  return rc::gen::exec([] {
    const std::int32_t v = *rc::gen::inRange(300, 3001);
    const std::int32_t a = *rc::gen::inRange(1000, 20001);
    const std::int32_t j = *rc::gen::inRange(std::max(a, 20000), std::min(1000 * a, 400000) + 1);
    return limits(v, a, j);
  });
}

// ---- the checker on hand-made traces: each rule can fail ------------------------------------

// The limits of the hand-made traces: v_max 1000 moves/s, a_max 2000, j_max 20000.
cr::Config hand_made_config() {
  cr::Config c;
  c.v_max = 1000;
  c.a_max = 2000;
  c.j_max = 20000;
  return c;
}

TEST(PathChainRules, TheCheckerCatchesASpeedAboveTheArcsCapAtTheJoin) {
  cr::ChainChecker k(hand_made_config(), {0, 0});
  k.accepted({cr::Kind::Line, {0, 0}, {10, 0}, {}});
  k.accepted({cr::Kind::ArcCcw, {10, 0}, {10, 20}, {10, 10}});  // r 10: cap sqrt(2000 * 10) = 141
  k.path_end();
  for (std::int64_t x = 1; x <= 10; ++x) k.tick({x, 0}, {200000, 0}, {1, 0});  // 200 moves/s on the line: fine
  EXPECT_TRUE(k.ok()) << k.report();
  k.tick({11, 0}, {200000, 0}, {1, 0});  // onto the arc at 200 > 141
  ASSERT_FALSE(k.ok());
  EXPECT_EQ(k.violations().front().rule, "cap.segment");
}

TEST(PathChainRules, TheCheckerCatchesAFullQueueOfOneChainThatNeverStarts) {
  cr::ChainChecker k(hand_made_config(), {0, 0});
  for (std::int64_t s = 0; s < 16; ++s) k.accepted({cr::Kind::Line, {s * 10, 0}, {s * 10 + 10, 0}, {}});
  k.refused_queue_full();
  for (int t = 0; t < 2000 && k.ok(); ++t) k.tick({0, 0}, {0, 0}, {0, 0});
  ASSERT_FALSE(k.ok());
  EXPECT_EQ(k.violations().front().rule, "live.start");
}

TEST(PathChainRules, TheCheckerCatchesACornerPassedAtSpeedAndAnOpenChainStarted) {
  cr::ChainChecker k(hand_made_config(), {0, 0});
  k.accepted({cr::Kind::Line, {0, 0}, {3, 0}, {}});
  k.tick({1, 0}, {100000, 0}, {1, 0});  // an open chain (no path_end, queue not full) moving
  ASSERT_FALSE(k.ok());
  EXPECT_EQ(k.violations().front().rule, "start.open");
  cr::ChainChecker q(hand_made_config(), {0, 0});
  q.accepted({cr::Kind::Line, {0, 0}, {3, 0}, {}});
  q.accepted({cr::Kind::Line, {3, 0}, {3, 3}, {}});  // a 90 degree corner
  q.path_end();
  q.tick({1, 0}, {100000, 0}, {1, 0});
  q.tick({2, 0}, {100000, 0}, {1, 0});
  q.tick({3, 1}, {100000, 100000}, {1, 1});
  ASSERT_FALSE(q.ok());
  EXPECT_EQ(q.violations().front().rule, "corner.rest");
}

TEST(PathChainRules, TheCheckerCatchesAPathThatOutlastsItsChainsTime) {
  cr::ChainChecker k(hand_made_config(), {0, 0});
  k.accepted({cr::Kind::Line, {0, 0}, {100, 0}, {}});
  k.path_end();
  // 100 moves at a cap of 1000 moves/s take well under 2 s; this board creeps at 20 moves/s.
  std::int64_t x = 0;
  for (int t = 1; t <= 5000 && k.ok(); ++t) {
    const bool step = t % 50 == 0;
    if (step) ++x;
    k.tick({x, 0}, {20000, 0}, {step ? 1 : 0, 0});
  }
  ASSERT_FALSE(k.ok());
  EXPECT_EQ(k.violations().front().rule, "live.end") << k.report();
  EXPECT_LT(x, 100);
}

// ---- the executor under the checker ------------------------------------------------------------

// docs/cnc.md "Speeds": a tangent line into a small arc. The line alone may run at v_max; the
// arc's cap sqrt(a_max r) limits the chain, so the carriage enters the arc within it.
TEST(PathChainRules, ALineIntoASmallTangentArcEntersItWithinTheArcsCap) {
  const auto lim = limits(2000, 5000, 100000);
  const std::vector<cr::Segment> segs{
      {cr::Kind::Line, {0, 0}, {4000, 0}, {}},
      {cr::Kind::ArcCcw, {4000, 0}, {4000, 40}, {4000, 20}},  // r 20: cap sqrt(5000 * 20) = 316
      {cr::Kind::Line, {4000, 40}, {0, 40}, {}},
  };
  const Streamed r = stream(segs, lim, 1);
  EXPECT_TRUE(r.unexpected.empty()) << r.unexpected;
  EXPECT_TRUE(r.chk.ok()) << r.chk.report();
  EXPECT_EQ(r.pos, (cr::Point{0, 40}));
  // The arc was run, and at a speed within its cap.
  EXPECT_GT(r.chk.max_arc_speed_over_cap(), 0.0);
  EXPECT_LE(r.chk.max_arc_speed_over_cap(), 1.0 + 1e-6);
}

// An arc into a tangent line and on into another small arc: the cap holds on both sides.
TEST(PathChainRules, SmallArcsJoinedByTangentLinesKeepEveryCap) {
  const auto lim = limits(3000, 20000, 400000);
  std::vector<cr::Segment> segs;
  cr::Point at{0, 0};
  for (int k = 0; k < 6; ++k) {
    const cr::Segment l = line_along(at, {1, 0}, 1500);
    segs.push_back(l);
    const cr::Segment a = tangent_arc(l.end, {1, 0}, 3 + 4 * k, k % 2 == 0, 360);  // full small circles
    segs.push_back(a);
    at = a.end;
  }
  const Streamed r = stream(segs, lim, 1);
  EXPECT_TRUE(r.unexpected.empty()) << r.unexpected;
  EXPECT_TRUE(r.chk.ok()) << r.chk.report();
  EXPECT_EQ(r.pos, segs.back().end);
  EXPECT_LE(r.chk.max_arc_speed_over_cap(), 1.0 + 1e-6);
}

// docs/cnc.md "Chains": the queue full with one open tangent chain starts it. The PC streams a
// tangent contour of 40 segments (lines and arcs) and waits for queue space before it sends
// the rest and the end: the chain must start without its end, and every wait must end.
TEST(PathChainRules, AFullQueueOfOneTangentChainStartsWithoutItsEnd) {
  const auto lim = limits(1500, 8000, 200000);
  std::vector<cr::Segment> segs;
  cr::Point at{0, 0};
  cr::Point d{0, 1};
  for (int k = 0; k < 20; ++k) {
    const cr::Segment l = line_along(at, d, 300);
    segs.push_back(l);
    const cr::Segment a = tangent_arc(l.end, d, 10 + k, k % 2 == 0, 180);  // a meander of half circles
    segs.push_back(a);
    at = a.end;
    d = {-d[0], -d[1]};
  }
  for (std::size_t k = 0; k + 1 < segs.size(); ++k) ASSERT_TRUE(cr::tangent(segs[k], segs[k + 1])) << k;
  const Streamed r = stream(segs, lim, 1);
  EXPECT_TRUE(r.unexpected.empty()) << r.unexpected;
  EXPECT_TRUE(r.chk.ok()) << r.chk.report();
  EXPECT_EQ(r.delivered, segs.size());
  EXPECT_EQ(r.pos, segs.back().end);
  // The path moved before the PC could send its end: the full queue started the chain.
  ASSERT_TRUE(r.chk.path_end_sent());
  EXPECT_LT(r.chk.first_motion_tick(), r.chk.path_end_tick());
}

// The same with a PC that sends frames as fast as the board takes them (16 at once).
TEST(PathChainRules, APcThatFillsTheQueueAtOnceGetsSpaceAgain) {
  const auto lim = limits(1000, 4000, 100000);
  std::vector<cr::Segment> segs;
  cr::Point at{0, 0};
  for (int k = 0; k < 50; ++k) {
    const cr::Segment l = line_along(at, {1, 1}, 20 + k);  // one straight diagonal in 50 pieces
    segs.push_back(l);
    at = l.end;
  }
  const Streamed r = stream(segs, lim, 16);
  EXPECT_TRUE(r.unexpected.empty()) << r.unexpected;
  EXPECT_TRUE(r.chk.ok()) << r.chk.report();
  EXPECT_EQ(r.delivered, segs.size());
  EXPECT_EQ(r.pos, segs.back().end);
  EXPECT_LT(r.chk.first_motion_tick(), r.chk.path_end_tick());
}

// A contour whose first chain runs at a unit arc's cap, sqrt(1000 * 1 / 2) = 22 moves/s, over
// thousands of moves: it must end where it should, later than the 400 000 ticks the harness
// used to allow (which made these false hangs), within the checker's live.end bound.
void expect_a_slow_chain_ends(const std::vector<cr::Segment>& segs, const ap::xy_path::Limits& lim) {
  const Streamed r = stream(segs, lim, 1);
  EXPECT_TRUE(r.unexpected.empty()) << r.unexpected;
  EXPECT_TRUE(r.chk.ok()) << r.chk.report();
  EXPECT_FALSE(r.active);
  EXPECT_EQ(r.delivered, segs.size());
  EXPECT_EQ(r.pos, segs.back().end);
  EXPECT_GT(r.chk.ticks(), 400000U);
}

// Two contours the random property found (seeds 8671320251570440452 and 4198763284520829351,
// shrunk): a small arc early in a long tangent chain caps the whole chain (docs/cnc.md "Speeds":
// the cap is the chain's), so the path runs for minutes at a few dozen moves/s. Both must end
// where they should, within the docs' time bound for their chains.
TEST(PathChainRules, ALongChainCappedByAnEarlyUnitArcEnds) {
  const auto lim = limits(300, 1000, 20000);
  using K = cr::Kind;
  std::vector<cr::Segment> segs{
      {K::Line, {0, 0}, {-1, -1}, {}},
      {K::Line, {-1, -1}, {-2, -2}, {}},
      {K::ArcCw, {-2, -2}, {-3, -2}, {-3, -1}},
      {K::ArcCw, {-3, -2}, {-23, 8}, {-3, 23}},
      {K::Line, {-23, 8}, {-26, 12}, {}},
      {K::ArcCcw, {-26, 12}, {-2561, -1504}, {-1214, -879}},
      {K::Line, {-2561, -1504}, {-1936, -2851}, {}},
      {K::ArcCw, {-1936, -2851}, {-4649, -2893}, {-3283, -3476}},
      {K::Line, {-4649, -2893}, {-4066, -1527}, {}},
      {K::ArcCcw, {-4066, -1527}, {-6555, -1916}, {-5432, -944}},
  };
  expect_a_slow_chain_ends(segs, lim);
}

TEST(PathChainRules, ALongChainCappedByAnEarlyUnitArcAndAFullCircleEnds) {
  const auto lim = limits(300, 1000, 20000);
  using K = cr::Kind;
  std::vector<cr::Segment> segs{
      {K::Line, {0, 0}, {-1, -1}, {}},
      {K::ArcCw, {-1, -1}, {-2, -1}, {-2, 0}},
      {K::ArcCw, {-2, -1}, {-551, 2961}, {-2, 1531}},
      {K::Line, {-551, 2961}, {879, 3510}, {}},
      {K::Line, {879, 3510}, {2309, 4059}, {}},
      {K::Line, {2309, 4059}, {1412, 2265}, {}},
      {K::Line, {1412, 2265}, {1394, 2229}, {}},
      {K::Line, {1394, 2229}, {226, -107}, {}},
      {K::Line, {226, -107}, {-572, -1703}, {}},
      {K::ArcCw, {-572, -1703}, {-572, -1703}, {-574, -1702}},
      {K::Line, {-572, -1703}, {-783, -2125}, {}},
      {K::Line, {-783, -2125}, {-788, -2131}, {}},
      {K::Line, {-788, -2131}, {-828, -2171}, {}},
      {K::Line, {-828, -2171}, {-1513, -2856}, {}},
      {K::Line, {-1513, -2856}, {-1514, -2857}, {}},
      {K::ArcCw, {-1514, -2857}, {-1515, -2857}, {-1515, -2856}},
      {K::Line, {-1515, -2857}, {-1848, -2857}, {}},
  };
  expect_a_slow_chain_ends(segs, lim);
}

// Random contours, streamed one segment a tick or in bursts, every rule of the checker.
RC_GTEST_PROP(PathChainRulesProps, RandomContoursStreamedByAPcKeepEveryChainRule, ()) {
  const auto segs = *gen_contour(1, 24, 25, 3000, 2500);
  const auto lim = *gen_limits();
  const std::size_t burst = *rc::gen::element<std::size_t>(1, 1, 3, 16);
  const Streamed r = stream(segs, lim, burst);
  if (r.unexpected.find("too long") != std::string::npos) RC_DISCARD("a contour beyond the documented ranges");
  RC_ASSERT(r.unexpected.empty());
  if (!r.chk.ok()) RC_FAIL(r.chk.report());
  RC_ASSERT(!r.active);
  RC_ASSERT(r.delivered == segs.size());
  RC_ASSERT(r.pos == segs.back().end);
}

// Tangent contours longer than the queue, the PC waiting for space: no deadlock, and the
// chain starts before the PC can send its end.
RC_GTEST_PROP(PathChainRulesProps, TangentContoursLongerThanTheQueueNeverDeadlock, ()) {
  const auto segs = *gen_contour(17, 40, 0, 600, 400);
  const auto lim = *gen_limits();
  const Streamed r = stream(segs, lim, *rc::gen::element<std::size_t>(1, 2, 16));
  if (r.unexpected.find("too long") != std::string::npos) RC_DISCARD("a contour beyond the documented ranges");
  RC_ASSERT(r.unexpected.empty());
  if (!r.chk.ok()) RC_FAIL(r.chk.report());
  RC_ASSERT(!r.active);
  RC_ASSERT(r.delivered == segs.size());
  RC_ASSERT(r.pos == segs.back().end);
  RC_ASSERT(r.chk.first_motion_tick() < r.chk.path_end_tick());
}

}  // namespace
