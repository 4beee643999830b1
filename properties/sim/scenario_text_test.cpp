// The plumbing the profiles' scenario languages share (sim/scenario_text.hpp), suite
// SimScenarioText: times in exact microseconds under each dialect's limits, words and strings
// with each dialect's escapes (and quoted back), the line shown in a report, the end-of-line
// messages, the comparisons (exact and within a tolerance), and the file:line error. Each
// profile's own statements are tested with its parser (properties/<profile>/sim,
// properties/<profile>/scenario).
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/scenario_text.hpp"

namespace t = ap::sim::text;

namespace {

// The two dialects as the profiles configure them (each profile's sim/<profile>/src/scenario.cpp).
const t::Dialect kFull = {
    .full_escapes = true, .name_at_end = false, .cut_blank_hash = true, .one_title = false, .time = {20, 1'000'000'000'000LL}};
const t::Dialect kPlain = {
    .full_escapes = false, .name_at_end = true, .cut_blank_hash = false, .one_title = true, .time = {15, 86'400'000'000LL}};

std::string error_of(const std::string& raw, const t::Dialect& d, void (*use)(t::Line&)) {
  try {
    t::Line l("f.scn", 7, raw, d);
    use(l);
  } catch (const t::ParseError& e) {
    EXPECT_EQ(e.line(), 7);
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SimScenarioText, TimesAreExactMicroseconds) {
  for (const t::Dialect& d : {kFull, kPlain}) {
    std::int64_t us = 0;
    EXPECT_TRUE(t::parse_time("0.52", "ms", us, d.time));
    EXPECT_EQ(us, 520);
    EXPECT_TRUE(t::parse_time("1.25", "s", us, d.time));
    EXPECT_EQ(us, 1'250'000);
    EXPECT_TRUE(t::parse_time("1327200", "us", us, d.time));
    EXPECT_EQ(us, 1'327'200);
    EXPECT_TRUE(t::parse_time("0.000001", "s", us, d.time));
    EXPECT_EQ(us, 1);
    EXPECT_TRUE(t::parse_time("2.000", "us", us, d.time));
    EXPECT_EQ(us, 2);
    EXPECT_FALSE(t::parse_time("0.5", "us", us, d.time));  // finer than 1 us
    EXPECT_FALSE(t::parse_time("0.0000001", "s", us, d.time));
    EXPECT_FALSE(t::parse_time("0.0015", "ms", us, d.time));
    EXPECT_FALSE(t::parse_time("-1", "s", us, d.time));
    EXPECT_FALSE(t::parse_time("1", "min", us, d.time));
    EXPECT_FALSE(t::parse_time(".", "s", us, d.time));
    EXPECT_FALSE(t::parse_time("1.2.3", "s", us, d.time));
    EXPECT_FALSE(t::parse_time("", "s", us, d.time));
  }
}

TEST(SimScenarioText, TimesStopAtTheDialectsLimits) {
  std::int64_t us = 0;
  // Up to 10^12 us and 20 characters (the full dialect), a day and 15 characters (the plain one).
  EXPECT_TRUE(t::parse_time("1000000", "s", us, kFull.time));
  EXPECT_EQ(us, 1'000'000'000'000LL);
  EXPECT_FALSE(t::parse_time("1000000.000001", "s", us, kFull.time));
  EXPECT_TRUE(t::parse_time("86400", "s", us, kPlain.time));
  EXPECT_EQ(us, 86'400'000'000LL);
  EXPECT_FALSE(t::parse_time("86400.000001", "s", us, kPlain.time));
  EXPECT_TRUE(t::parse_time("0000000000000001", "us", us, kFull.time));  // 16 characters
  EXPECT_FALSE(t::parse_time("0000000000000001", "us", us, kPlain.time));
  EXPECT_FALSE(t::parse_time("000000000000000000001", "us", us, kFull.time));  // 21
  EXPECT_FALSE(t::parse_time("99999999999999999999", "us", us, kFull.time));   // past int64
}

TEST(SimScenarioText, WordsStringsAndComments) {
  const auto toks = t::tokenize("  at 10ms send \"a b\\\"\" # comment \"x", "f.scn", 1, kPlain);
  ASSERT_EQ(toks.size(), 4U);
  EXPECT_EQ(toks[0].text, "at");
  EXPECT_EQ(toks[1].text, "10ms");
  EXPECT_FALSE(toks[2].quoted);
  EXPECT_TRUE(toks[3].quoted);
  EXPECT_EQ(toks[3].text, "a b\"");
  EXPECT_TRUE(t::tokenize("   # only a comment", "f.scn", 1, kPlain).empty());
  // The full dialect's escapes: the line's control bytes.
  const auto full = t::tokenize("\"\\r\\n\\t\\x41\\\\\"", "f.scn", 1, kFull);
  ASSERT_EQ(full.size(), 1U);
  EXPECT_EQ(full[0].text, "\r\n\tA\\");
}

TEST(SimScenarioText, StringErrorsNameTheFileAndLine) {
  const auto err = [](const std::string& raw, const t::Dialect& d) {
    try {
      t::tokenize(raw, "f.scn", 4, d);
    } catch (const t::ParseError& e) {
      EXPECT_EQ(e.line(), 4);
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(err("title \"abc", kPlain), "f.scn:4: unterminated string");
  EXPECT_EQ(err("title \"abc", kFull), "f.scn:4: unterminated string");
  EXPECT_EQ(err("title \"ab\\", kFull), "f.scn:4: unterminated string");
  EXPECT_EQ(err("title \"ab\\", kPlain), "f.scn:4: unterminated string");  // a backslash ends the line
  EXPECT_EQ(err("title \"\\q\"", kPlain), "f.scn:4: a string escapes only \\\" and \\\\");
  EXPECT_EQ(err("title \"\\n\"", kPlain), "f.scn:4: a string escapes only \\\" and \\\\");
  EXPECT_EQ(err("title \"\\q\"", kFull), "f.scn:4: unknown escape \\q");
  EXPECT_EQ(err("send \"\\x4\"", kFull), "f.scn:4: \\x needs two hex digits");
}

TEST(SimScenarioText, TheLineAsShown) {
  // The full dialect cuts at " #" unless the line holds a string, and keeps trailing blanks.
  EXPECT_EQ(t::shown("  expect end pulses y == 5 # five", kFull), "expect end pulses y == 5");
  EXPECT_EQ(t::shown("expect reply \"S\" # c", kFull), "expect reply \"S\" # c");
  EXPECT_EQ(t::shown("expect end x#y", kFull), "expect end x#y");
  // The plain one cuts at '#' and drops trailing blanks.
  EXPECT_EQ(t::shown("\texpect end steps == 5   # five", kPlain), "expect end steps == 5");
  EXPECT_EQ(t::shown("expect end steps == 5 \r", kPlain), "expect end steps == 5");
}

TEST(SimScenarioText, LineReadsWordsTimesAndComparisons) {
  t::Line l("f.scn", 3, "at 10ms 0.5 s \"x\" <= end", kPlain);
  EXPECT_EQ(l.number(), 3);
  EXPECT_TRUE(l.peek_is("at"));
  l.expect_word("at");
  EXPECT_EQ(l.time(), 10'000);
  EXPECT_EQ(l.time(), 500'000);
  EXPECT_EQ(l.string("a string"), "x");
  EXPECT_EQ(l.op(), t::Op::Le);
  EXPECT_FALSE(l.peek_is("\"end\""));
  EXPECT_EQ(l.word("end"), "end");
  EXPECT_TRUE(l.done());
  l.end();
}

TEST(SimScenarioText, LinePeeksAndAcceptsWords) {
  t::Line l("f.scn", 3, "tol \"tol\" 5", kPlain);
  ASSERT_NE(l.peek(), nullptr);
  EXPECT_EQ(l.peek()->text, "tol");
  EXPECT_FALSE(l.peek()->quoted);
  EXPECT_FALSE(l.accept("to"));
  EXPECT_TRUE(l.accept("tol"));
  ASSERT_NE(l.peek(), nullptr);
  EXPECT_TRUE(l.peek()->quoted);
  EXPECT_FALSE(l.accept("tol"));  // a string is no word
  EXPECT_EQ(l.string("a string"), "tol");
  EXPECT_TRUE(l.accept("5"));
  EXPECT_EQ(l.peek(), nullptr);
  EXPECT_FALSE(l.accept("5"));
  l.end();
}

TEST(SimScenarioText, LineErrors) {
  const auto word = [](t::Line& l) { (void)l.word("a statement"); };
  const auto end = [](t::Line& l) {
    (void)l.word("a");
    l.end();
  };
  const auto time = [](t::Line& l) { (void)l.time(); };
  const auto op = [](t::Line& l) { (void)l.op(); };
  const auto str = [](t::Line& l) { (void)l.string("the title"); };
  const auto two = [](t::Line& l) {
    (void)l.word("a");
    (void)l.word("a key");
  };
  EXPECT_EQ(error_of("a", kFull, two), "f.scn:7: unexpected end of line");
  EXPECT_EQ(error_of("a", kPlain, two), "f.scn:7: expected a key at the end of the line");
  EXPECT_EQ(error_of("\"s\"", kPlain, word), "f.scn:7: expected a statement, got a string");
  EXPECT_EQ(error_of("a extra", kFull, end), "f.scn:7: unexpected 'extra' at the end of the line");
  EXPECT_EQ(error_of("10", kPlain, time), "f.scn:7: time '10' needs a unit (s, ms, us)");
  EXPECT_EQ(error_of("10 parsecs", kPlain, time), "f.scn:7: bad time '10 parsecs' (a number and s, ms or us, whole us)");
  EXPECT_EQ(error_of("=<", kFull, op), "f.scn:7: unknown comparison '=<' (== != < <= > >=)");
  EXPECT_EQ(error_of("abc", kFull, str), "f.scn:7: expected the title as a \"string\", got 'abc'");
  const auto expect_c = [](t::Line& l) {
    l.expect_word("a");
    l.expect_word("c");
  };
  EXPECT_EQ(error_of("a b", kPlain, expect_c), "f.scn:7: expected 'c', got 'b'");
}

TEST(SimScenarioText, Comparisons) {
  using t::Op;
  const std::vector<std::pair<Op, const char*>> ops = {{Op::Eq, "=="}, {Op::Ne, "!="}, {Op::Lt, "<"},
                                                       {Op::Le, "<="}, {Op::Gt, ">"},  {Op::Ge, ">="}};
  for (const auto& [op, text] : ops) EXPECT_STREQ(t::op_text(op), text);
  EXPECT_TRUE(t::compare(3, Op::Eq, 3));
  EXPECT_FALSE(t::compare(3, Op::Eq, 4));
  EXPECT_TRUE(t::compare(3, Op::Ne, 4));
  EXPECT_FALSE(t::compare(3, Op::Ne, 3));
  EXPECT_TRUE(t::compare(3, Op::Lt, 4));
  EXPECT_FALSE(t::compare(4, Op::Lt, 4));
  EXPECT_TRUE(t::compare(4, Op::Le, 4));
  EXPECT_FALSE(t::compare(5, Op::Le, 4));
  EXPECT_TRUE(t::compare(5, Op::Gt, 4));
  EXPECT_FALSE(t::compare(4, Op::Gt, 4));
  EXPECT_TRUE(t::compare(4, Op::Ge, 4));
  EXPECT_FALSE(t::compare(3, Op::Ge, 4));
}

TEST(SimScenarioText, ComparisonsAreReadFromTheirSpelling) {
  using t::Op;
  for (const Op op : {Op::Eq, Op::Ne, Op::Lt, Op::Le, Op::Gt, Op::Ge}) {
    ASSERT_TRUE(t::op_of(t::op_text(op)).has_value());
    EXPECT_EQ(*t::op_of(t::op_text(op)), op);
  }
  for (const char* w : {"", "=", "=<", "=>", "<>", "===", "eq", "<= "}) EXPECT_FALSE(t::op_of(w).has_value()) << w;
}

// compare_within: tol widens every comparison, slack only ==, !=, <= and >=.
TEST(SimScenarioText, ComparisonsWithinATolerance) {
  using t::Op;
  struct Row {
    Op op;
    double got;
    bool exact;     // tol 0, slack 0
    bool with_tol;  // tol 2
  };
  const std::vector<Row> rows{
      {Op::Eq, 101.0, false, true}, {Op::Eq, 100.0, true, true},  {Op::Eq, 103.0, false, false},
      {Op::Ne, 101.0, true, false}, {Op::Ne, 100.0, false, false}, {Op::Ne, 103.0, true, true},
      {Op::Lt, 100.0, false, true}, {Op::Lt, 99.0, true, true},    {Op::Lt, 102.0, false, false},
      {Op::Le, 100.0, true, true},  {Op::Le, 101.0, false, true},  {Op::Le, 102.5, false, false},
      {Op::Gt, 100.0, false, true}, {Op::Gt, 101.0, true, true},   {Op::Gt, 98.0, false, false},
      {Op::Ge, 100.0, true, true},  {Op::Ge, 99.0, false, true},   {Op::Ge, 97.5, false, false},
  };
  for (const Row& r : rows) {
    SCOPED_TRACE(std::string(t::op_text(r.op)) + " " + std::to_string(r.got));
    EXPECT_EQ(t::compare_within(r.got, r.op, 100.0, 0.0, 0.0), r.exact);
    EXPECT_EQ(t::compare_within(r.got, r.op, 100.0, 2.0, 0.0), r.with_tol);
  }
  // A value just past the bound: the slack lets ==, !=, <= and >= count it as on the bound.
  const double up = 100.0 + 1e-12, down = 100.0 - 1e-12;
  EXPECT_FALSE(t::compare_within(up, Op::Eq, 100.0, 0.0, 0.0));
  EXPECT_TRUE(t::compare_within(up, Op::Eq, 100.0, 0.0, 1e-9));
  EXPECT_TRUE(t::compare_within(up, Op::Ne, 100.0, 0.0, 0.0));
  EXPECT_FALSE(t::compare_within(up, Op::Ne, 100.0, 0.0, 1e-9));
  EXPECT_FALSE(t::compare_within(up, Op::Le, 100.0, 0.0, 0.0));
  EXPECT_TRUE(t::compare_within(up, Op::Le, 100.0, 0.0, 1e-9));
  EXPECT_FALSE(t::compare_within(down, Op::Ge, 100.0, 0.0, 0.0));
  EXPECT_TRUE(t::compare_within(down, Op::Ge, 100.0, 0.0, 1e-9));
  // The strict ones take none: on the bound stays outside.
  EXPECT_FALSE(t::compare_within(100.0, Op::Lt, 100.0, 0.0, 1e-9));
  EXPECT_FALSE(t::compare_within(100.0, Op::Gt, 100.0, 0.0, 1e-9));
  EXPECT_TRUE(t::compare_within(down, Op::Lt, 100.0, 0.0, 1e-9));
  EXPECT_FALSE(t::compare_within(up, Op::Lt, 100.0, 0.0, 1e-9));
}

// quote() is the tokenizer's inverse: what it writes reads back as the same bytes.
TEST(SimScenarioText, QuotedStringsReadBack) {
  EXPECT_EQ(t::quote("a \"b\" \\ # c", kPlain), "\"a \\\"b\\\" \\\\ # c\"");
  EXPECT_EQ(t::quote("", kPlain), "\"\"");
  EXPECT_EQ(t::quote("D+;\r\n\t\x01\x7f\"", kFull), "\"D+;\\r\\n\\t\\x01\\x7f\\\"\"");
  std::string every;  // every byte; the plain dialect has no escape for a line break
  for (int b = 0; b < 256; ++b) every += static_cast<char>(b);
  std::string no_break = every;
  no_break.erase(static_cast<std::size_t>('\n'), 1);
  for (const auto& [d, text] : {std::make_pair(kFull, every), std::make_pair(kPlain, no_break)}) {
    const auto toks = t::tokenize("raw " + t::quote(text, d) + " # c", "f.scn", 1, d);
    ASSERT_EQ(toks.size(), 2U);
    EXPECT_TRUE(toks[1].quoted);
    EXPECT_EQ(toks[1].text, text);
  }
}

TEST(SimScenarioText, NamesAndFiles) {
  EXPECT_TRUE(t::valid_name("mode_b-90"));
  EXPECT_FALSE(t::valid_name(""));
  EXPECT_FALSE(t::valid_name("bad/name"));
  try {
    (void)t::read_file("/nonexistent/axisproof/none.scn");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot read scenario /nonexistent/axisproof/none.scn");
  }
  const t::ParseError e("a.scn", 12, "what");
  EXPECT_STREQ(e.what(), "a.scn:12: what");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.file(), "a.scn");
}

TEST(SimScenarioText, TheHeaderStatements) {
  const auto header = [](const std::string& text, const t::Dialect& d) {
    t::Header h;
    std::vector<std::string> others;
    const int n = t::each_statement(text, "h.scn", d, [&](t::Line& l, const std::string& shown) {
      if (!h.read(l.word("a statement"), l)) others.push_back(shown);
    });
    h.check("h.scn", n);
    return std::make_pair(h, others);
  };
  const auto [h, others] = header("# a comment\nscenario s-1\n\ntitle \"T\"\nduration 2 s\nexpect end x # y\n", kPlain);
  EXPECT_EQ(h.name, "s-1");
  EXPECT_EQ(h.title, "T");
  EXPECT_EQ(h.duration_us, 2'000'000);
  ASSERT_EQ(others.size(), 1U);
  EXPECT_EQ(others[0], "expect end x");
  const auto error = [&](const std::string& text, const t::Dialect& d) {
    try {
      header(text, d);
    } catch (const t::ParseError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string ok = "scenario s\nduration 1 s\n";
  EXPECT_EQ(error(ok + "title \"a\"\ntitle \"b\"\n", kPlain), "h.scn:4: a second 'title' line");
  EXPECT_EQ(error(ok + "title \"a\"\ntitle \"b\"\n", kFull), "");
  EXPECT_EQ(error(ok + "scenario t\n", kFull), "h.scn:3: a second 'scenario' line");
  EXPECT_EQ(error(ok + "duration 2 s\n", kFull), "h.scn:3: a second 'duration' line");
  EXPECT_EQ(error("scenario s\nduration 1.5 ms\n", kPlain), "h.scn:2: the duration is whole ms, at least 1 ms");
  EXPECT_EQ(error("scenario s\nduration 0 ms\n", kPlain), "h.scn:2: the duration is whole ms, at least 1 ms");
  EXPECT_EQ(error("scenario a/b\n", kPlain), "h.scn:1: scenario name 'a/b': letters, digits, _ and - only");
  EXPECT_EQ(error("scenario s\n\n", kFull), "h.scn:2: no 'duration' line");
  EXPECT_EQ(error("duration 1 s\n", kFull), "h.scn:1: no 'scenario NAME' line");
  EXPECT_EQ(error("scenario s extra\n", kFull), "h.scn:1: unexpected 'extra' at the end of the line");
}
