// PC client against an independent oracle of its queue and seq rules (client_rules_model.hpp,
// written from docs/protocol.md "Delivery" rules 1-6 and the "Commands" table):
//   - which queued commands a stop supersedes, for every command ID of the table, stops of
//     either axis, and in which order and groups the others leave (rules 4 and 5);
//   - the seq of every new frame, across the wrap and after a board found ahead of the client
//     by 1..500 (another sender, or a PC program restarted at seq 000): the renumbered frame
//     and every new frame after it must be new to the board, which runs a frame only when its
//     seq is newer than the last one it took (the board's seq table; xy_codec::seq_order is the
//     shared arithmetic the document names).
// The expectations come from the model and the document, never from client.cpp.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "client_rules_model.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "pc/xy/client/client.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/layout.hpp"

namespace {

namespace f = ap::xy_frame;
namespace c = ap::xy_codec;
namespace m = ap::test::client_rules;
using ap::xy_client::Client;
using ap::xy_client::EchoKind;
using ap::xy_client::Outcome;
using m::Ticket;
using C = c::CommandId;

// Rule 3: with nothing queued a frame leaves every 100 ms; rule 1: the frame in flight is
// repeated after 40 ms (commands) or the keep-alive period (none). The harness polls once per
// 100 ms, so every poll sends something: a new frame when nothing is in flight, else a repeat.
constexpr std::int64_t kPeriodUs = 100'000;

// The harness is shared by RapidCheck properties and plain tests: a failed check throws, which
// fails (and shrinks) a property and fails a TEST with the check's text and line.
#define RULE_CHECK(cond)                                                                                      \
  do {                                                                                                        \
    if (!(cond)) throw std::runtime_error(std::string(__FILE__ ":") + std::to_string(__LINE__) + ": " #cond); \
  } while (false)

ap::xy_client::Part to_client(m::Part p) {
  return p == m::Part::X ? ap::xy_client::Part::X : p == m::Part::Y ? ap::xy_client::Part::Y : ap::xy_client::Part::Unit;
}

const char* part_name(m::Part p) { return p == m::Part::X ? "x" : p == m::Part::Y ? "y" : "unit"; }

f::CommandFrame parsed(const std::string& bytes) {
  f::CommandFrame fr;
  const auto r =
      f::parse_command(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), fr);
  RULE_CHECK(r.ok());
  return fr;
}

// The board's answer to a frame it took and ran: both parts idle (outcome table: done).
std::string echo_with_seq(std::uint16_t seq) {
  return *ap::xy_client::format(f::EchoFrame{seq, {c::EchoStatus::Idle, 0}, {c::EchoStatus::Idle, 0}, {}});
}

// A command the tables admit, with its part from the model's scope column (an axis command for
// X or Y, a unit command for the unit); data drawn from the codec's range (the table's column).
rc::Gen<m::Cmd> genAnyCommand() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, m::kTableRows), [](std::size_t i) {
    const C id = static_cast<C>(i);
    const auto& info = c::info(id);
    const auto part = m::row(id).scope == m::Scope::Unit ? rc::gen::just(m::Part::Unit)
                                                          : rc::gen::element(m::Part::X, m::Part::Y);
    return rc::gen::apply([id](m::Part p, std::int32_t d) { return m::Cmd{p, id, d}; }, part,
                          rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1));
  });
}

rc::Gen<m::Cmd> genStop() {
  return rc::gen::map(rc::gen::element(m::Part::X, m::Part::Y), [](m::Part p) { return m::Cmd{p, C::Stop, 0}; });
}

// Stops drawn often, so that most runs have stops with queued commands of both axes before them.
rc::Gen<m::Cmd> genCommand() { return rc::gen::weightedOneOf<m::Cmd>({{3, genAnyCommand()}, {1, genStop()}}); }

struct Step {
  enum Kind { Submit, Poll, Answer } kind = Poll;
  m::Cmd cmd{};
};

std::ostream& operator<<(std::ostream& os, const Step& s) {
  if (s.kind == Step::Poll) return os << "poll";
  if (s.kind == Step::Answer) return os << "answer";
  return os << "submit " << part_name(s.cmd.part) << ' ' << c::info(s.cmd.id).key << ':' << s.cmd.data;
}

rc::Gen<Step> genStep() {
  return rc::gen::weightedOneOf<Step>({
      {6, rc::gen::map(genCommand(), [](m::Cmd cmd) { return Step{Step::Submit, cmd}; })},
      {2, rc::gen::just(Step{Step::Poll, {}})},
      {2, rc::gen::just(Step{Step::Answer, {}})},
  });
}

// The client and the model side by side; every difference fails the property at once.
struct Harness {
  explicit Harness(std::uint16_t first_seq) : cl(config(first_seq)), model(first_seq) {}

  static ap::xy_client::Config config(std::uint16_t first_seq) {
    ap::xy_client::Config cfg;
    cfg.first_seq = first_seq;
    // A client opened for factory work sends every row of the table (docs/storage.md "Factory
    // and user parameters"); otherwise pitch .. ihold would end `invalid` and never queue.
    cfg.factory = true;
    return cfg;
  }

  Ticket submit(const m::Cmd& cmd) {
    const Ticket t = cl.submit({to_client(cmd.part), {cmd.id, cmd.data}}, now);
    submitted.insert(t);
    std::vector<Ticket> expected = model.submit(t, cmd);
    std::vector<Ticket> got;
    for (const auto& r : cl.take_reports()) {
      RULE_CHECK(r.outcome == Outcome::Superseded);
      RULE_CHECK(!r.seq.has_value());  // "cancelled it before it was sent"
      got.push_back(r.ticket);
    }
    std::sort(expected.begin(), expected.end());
    std::sort(got.begin(), got.end());
    RULE_CHECK(got == expected);
    for (const Ticket g : got) RULE_CHECK(settled.emplace(g, std::nullopt).second);
    return t;
  }

  // One keep-alive period passes and the client is polled. Returns what it sent.
  std::string poll() {
    now += kPeriodUs;
    const auto out = cl.poll(now, {});
    RULE_CHECK(out.has_value());
    if (model.in_flight() && !renumbered) {
      RULE_CHECK(*out == in_flight_bytes);  // rule 1: a repeat, byte for byte
      return *out;
    }
    const m::Frame& want = renumbered ? model.frame_in_flight() : model.start_frame();
    const f::CommandFrame got = parsed(*out);
    RULE_CHECK(got.seq == want.seq);
    RULE_CHECK(got.x == (f::AxisCommand{want.part[0].id, want.part[0].data}));
    RULE_CHECK(got.y == (f::AxisCommand{want.part[1].id, want.part[1].data}));
    if (!renumbered) left.push_back(want);
    renumbered = false;
    in_flight_bytes = *out;
    return *out;
  }

  // The board answers the frame in flight with its own seq: its commands are done, each once.
  void answer(const std::string& echo) {
    const auto ev = cl.receive(echo, now);
    RULE_CHECK(ev.size() == 1U);
    RULE_CHECK(ev[0].kind == EchoKind::Answer);
    const m::Frame done = model.answered();
    std::vector<Ticket> expected = done.tickets;
    std::vector<Ticket> got;
    for (const auto& r : cl.take_reports()) {
      RULE_CHECK(r.outcome == Outcome::Done);
      RULE_CHECK(r.seq == std::optional<std::uint16_t>(done.seq));
      got.push_back(r.ticket);
      RULE_CHECK(settled.emplace(r.ticket, done.seq).second);
    }
    std::sort(expected.begin(), expected.end());
    std::sort(got.begin(), got.end());
    RULE_CHECK(got == expected);
  }

  void answer() {
    if (!model.in_flight()) return;
    answer(echo_with_seq(model.frame_in_flight().seq));
  }

  // Every command submitted ended exactly once: superseded, or done in the frame that carried it.
  void all_settled() const {
    RULE_CHECK(model.queued() == 0U);
    RULE_CHECK(!model.in_flight());
    RULE_CHECK(cl.idle());
    std::set<Ticket> ended;
    for (const auto& [t, seq] : settled) ended.insert(t);
    RULE_CHECK(ended == submitted);
  }

  Client cl;
  m::Model model;
  std::int64_t now = 0;
  std::string in_flight_bytes;
  bool renumbered = false;     // the model renumbered the frame in flight (rule 6)
  std::vector<m::Frame> left;  // the new frames, in the order they left
  // Per frame (index into `left`): how often the board took it, its answer was lost and then a
  // foreign seq came before the client heard back (exchange()).
  std::map<std::size_t, std::size_t> extra_runs;
  std::set<Ticket> submitted;
  std::map<Ticket, std::optional<std::uint16_t>> settled;  // seq of its frame; none = superseded
};

// (i) Random submits of every command ID on both axes and the unit, stops of random axes, polls
// and answers in random order; the superseded set, the frames (contents, so order and grouping)
// and the seqs must be the model's, and every command ends exactly once.
RC_GTEST_PROP(ProtocolClientRules, StopsSupersedeAndCommandsLeaveAsTheModelSays, ()) {
  const auto first_seq = *rc::gen::inRange<std::uint16_t>(0, c::kSeqModulo);
  const auto steps = *rc::gen::container<std::vector<Step>>(genStep());
  Harness h(first_seq);
  for (const Step& s : steps) {
    switch (s.kind) {
      case Step::Submit: h.submit(s.cmd); break;
      case Step::Poll: h.poll(); break;
      case Step::Answer: h.answer(); break;
    }
  }
  while (h.model.in_flight() || h.model.queued() > 0) {
    h.poll();
    h.answer();
  }
  h.all_settled();
  std::size_t superseded = 0;
  for (const auto& [t, seq] : h.settled) superseded += seq ? 0U : 1U;
  RC_CLASSIFY(superseded > 0, "some command superseded");
}

// Every row of the table, issued for each axis (unit rows for the unit) behind a frame in
// flight, then a stop of one axis: exactly the goto, move, home, jog, goto_slow and move_slow
// of that axis and the path's commands of both parts are superseded (rule 5 and the note
// under the table), and the rest leave in
// issue order behind the stop. Both axes, so a stop that cancels the other axis's commands
// fails too.
TEST(ProtocolClientRules, AStopSupersedesExactlyTheDocumentedMotionCommandsOfItsAxis) {
  for (const m::Part stopped : {m::Part::X, m::Part::Y}) {
    SCOPED_TRACE(part_name(stopped));
    Harness h(0);
    try {
      h.poll();  // a keep-alive is in flight: everything below stays queued
      std::map<Ticket, m::Cmd> issued;
      for (std::size_t i = 0; i < m::kTableRows; ++i) {
        const C id = static_cast<C>(i);
        if (id == C::Stop) continue;
        const std::int32_t d = c::info(id).range.max > 0 ? 1 : 0;
        if (m::row(id).scope == m::Scope::Unit) {
          issued.emplace(h.submit({m::Part::Unit, id, d}), m::Cmd{m::Part::Unit, id, d});
        } else {
          for (const m::Part p : {m::Part::X, m::Part::Y}) issued.emplace(h.submit({p, id, d}), m::Cmd{p, id, d});
        }
      }
      h.submit({stopped, C::Stop, 0});
      std::set<std::string> gone;
      for (const auto& [t, seq] : h.settled) {
        if (!seq) gone.insert(std::string(part_name(issued.at(t).part)) + " " + std::string(c::info(issued.at(t).id).key));
      }
      const std::string a = part_name(stopped);
      // Rule 5: and the path's commands of both parts, which a stop of either axis cancels.
      EXPECT_EQ(gone, (std::set<std::string>{a + " jog", a + " goto", a + " move", a + " home", a + " goto_slow",
                                             a + " move_slow", "x line", "y line", "x centre", "y centre", "x arc_cw",
                                             "y arc_cw", "x arc_ccw", "y arc_ccw", "unit path_end"}));
      while (h.model.in_flight() || h.model.queued() > 0) {
        h.poll();
        h.answer();
      }
      h.all_settled();
      // The stop left first, in the frame right after the keep-alive that was in flight.
      ASSERT_GE(h.left.size(), 2U);
      EXPECT_EQ(h.left[1].part[stopped == m::Part::X ? 0 : 1].id, C::Stop);
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

// The board's side of the seq (docs/protocol.md, the board's table): it keeps the last seq it
// took and judges each intact frame new, a repeat or older with xy_codec::seq_order.
struct Board {
  std::optional<std::uint16_t> last;
  std::vector<f::CommandFrame> taken;  // frames of this client it ran, in order
  std::vector<std::size_t> taken_index;  // which of the client's new frames each one was (Harness::left)

  c::SeqOrder judge(std::uint16_t seq) const { return last ? c::seq_order(*last, seq) : c::SeqOrder::New; }

  // Runs a new frame; answers anything with the seq of the last frame taken.
  std::string receive(const f::CommandFrame& fr, std::size_t index) {
    if (judge(fr.seq) == c::SeqOrder::New) {
      last = fr.seq;
      taken.push_back(fr);
      taken_index.push_back(index);
    }
    return echo_with_seq(*last);
  }

  // Another sender (or this PC program before a restart) had a frame taken.
  void foreign(std::uint16_t seq) { last = seq; }
  bool ahead_unseen = false;  // the client has not yet had an answer carrying the foreign seq
};

struct Exchange {
  std::optional<int> ahead;  // before this frame reaches the board, the board takes a foreign seq this far ahead of it
  bool echo_lost = false;    // the board's answer is lost on the way back
};

std::ostream& operator<<(std::ostream& os, const Exchange& e) {
  os << "exchange";
  if (e.ahead) os << " board-ahead " << *e.ahead;
  if (e.echo_lost) os << " echo-lost";
  return os;
}

rc::Gen<int> genAhead() {
  // 1..500 ahead (rule 6), its two ends drawn often.
  return rc::gen::weightedOneOf<int>({{1, rc::gen::just(1)}, {1, rc::gen::just(500)}, {4, rc::gen::inRange(1, 501)}});
}

// Up to three commands submitted between two exchanges.
rc::Gen<std::vector<m::Cmd>> genSubmits() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, 4),
                         [](std::size_t n) { return rc::gen::container<std::vector<m::Cmd>>(n, genCommand()); });
}

// One round: some submits, then one exchange (a poll, the board, maybe its echo).
struct Round {
  std::vector<m::Cmd> submits;
  Exchange exchange;
};

std::ostream& operator<<(std::ostream& os, const Round& r) {
  for (const m::Cmd& cmd : r.submits) os << Step{Step::Submit, cmd} << "; ";
  return os << r.exchange;
}

rc::Gen<Round> genRound() {
  return rc::gen::apply(
      [](std::vector<m::Cmd> s, std::optional<int> ahead, bool lost) { return Round{std::move(s), {ahead, lost}}; },
      genSubmits(),
      rc::gen::weightedOneOf<std::optional<int>>(
          {{4, rc::gen::just(std::optional<int>())}, {1, rc::gen::map(genAhead(), [](int a) { return std::optional<int>(a); })}}),
      rc::gen::weightedOneOf<bool>({{5, rc::gen::just(false)}, {1, rc::gen::just(true)}}));
}

// Drives the client against the board model: every frame the client sends must be what the
// model predicts and what the board's seq check expects -- a repeat is a repeat, and every new
// or renumbered frame is new to the board (else the board would answer it without running it:
// a command silently lost). Returns the board's verdict on the frame.
c::SeqOrder exchange(Harness& h, Board& board, const Exchange& x) {
  const bool repeat = h.model.in_flight() && !h.renumbered;
  const std::string bytes = h.poll();
  const f::CommandFrame fr = parsed(bytes);
  const std::size_t index = h.left.size() - 1;  // the frame in flight is the last one that left
  if (x.ahead) {
    // The board took this very frame already and only its answer was lost: the foreign frame
    // came after it, so the client cannot know, and the renumbered copy runs again. Rule 6
    // renumbers the frame in flight whatever happened to it; the exactly-once guarantee is about
    // one client on a faulty link, not about a second sender -- counted, not failed.
    if (board.last == fr.seq && board.taken_index.back() == index) ++h.extra_runs[index];
    board.foreign(static_cast<std::uint16_t>((fr.seq + *x.ahead) % c::kSeqModulo));
    board.ahead_unseen = true;
  }
  const c::SeqOrder order = board.judge(fr.seq);
  if (board.ahead_unseen) {
    // 1..500 ahead of the frame in flight: the board finds our frame 500..999 ahead of its last
    // one, i.e. older, runs nothing and answers with its own seq (the board's table) -- until
    // the client has seen that answer and renumbered (rule 6).
    RULE_CHECK(order == c::SeqOrder::Older);
  } else if (repeat) {
    RULE_CHECK(order == c::SeqOrder::Repeat);  // taken when first sent; only its answer was lost
  } else {
    RULE_CHECK(order == c::SeqOrder::New);  // a new or renumbered frame is new to the board
  }
  const std::string echo = board.receive(fr, index);
  if (x.echo_lost) return order;
  if (order == c::SeqOrder::Older) {
    const auto ev = h.cl.receive(echo, h.now);
    RULE_CHECK(ev.size() == 1U);
    RULE_CHECK(ev[0].kind == EchoKind::Resync);
    RULE_CHECK(h.cl.take_reports().empty());  // renumbering settles nothing
    RULE_CHECK(h.model.board_at(*board.last));
    h.renumbered = true;
    board.ahead_unseen = false;
    return order;
  }
  h.answer(echo);
  return order;
}

// (ii) The board is found ahead of the frame in flight by 1..500 seqs, at random points (the
// very first frame included) and possibly several times: the frame in flight goes out again
// renumbered to follow the board's seq, and the new frames after it continue from it; every one
// is new to the board; the board runs exactly the frames the model says left, in order.
RC_GTEST_PROP(ProtocolClientRules, AfterTheBoardIsFoundAheadNewFramesContinueFromTheRenumberedOne, ()) {
  const auto first_seq = *rc::gen::inRange<std::uint16_t>(0, c::kSeqModulo);
  auto rounds = *rc::gen::container<std::vector<Round>>(genRound());
  // At least one resync; half of the runs start with the board ahead of the client's first frame.
  const bool at_start = *rc::gen::arbitrary<bool>();
  const std::size_t at = at_start ? 0 : *rc::gen::inRange<std::size_t>(0, rounds.size() + 1);
  rounds.insert(rounds.begin() + static_cast<std::ptrdiff_t>(at), Round{*genSubmits(), {*genAhead(), false}});
  Harness h(first_seq);
  Board board;
  std::size_t since_resync = 0;
  for (const Round& r : rounds) {
    for (const m::Cmd& cmd : r.submits) h.submit(cmd);
    const c::SeqOrder o = exchange(h, board, r.exchange);
    since_resync = o == c::SeqOrder::Older ? 0 : since_resync + 1;
  }
  // Several more frames after the last resync (keep-alives when nothing is queued), each new.
  while (h.model.in_flight() || h.model.queued() > 0 || since_resync < 5) {
    exchange(h, board, {});
    ++since_resync;
  }
  h.all_settled();
  // Exactly once, in order: every frame that left ran, in the order it left, once -- again only once per foreign seq
  // that came between a run and its answer.
  RULE_CHECK(!board.taken.empty());
  std::map<std::size_t, std::size_t> runs;
  for (std::size_t i = 0; i < board.taken.size(); ++i) {
    const std::size_t k = board.taken_index[i];
    RULE_CHECK(i == 0 ? k == 0U : (k == board.taken_index[i - 1] || k == board.taken_index[i - 1] + 1));
    ++runs[k];
    RULE_CHECK(board.taken[i].x == (f::AxisCommand{h.left[k].part[0].id, h.left[k].part[0].data}));
    RULE_CHECK(board.taken[i].y == (f::AxisCommand{h.left[k].part[1].id, h.left[k].part[1].data}));
  }
  RULE_CHECK(runs.size() == h.left.size());
  for (const auto& [k, n] : runs) RULE_CHECK(n == 1 + (h.extra_runs.count(k) ? h.extra_runs.at(k) : 0U));
  RC_CLASSIFY(!h.extra_runs.empty(), "a frame taken, its answer lost, then the board found ahead");
}

// The same at its edges, spelled out: a fresh client (seq 000, and 998 across the wrap) whose
// board already took a frame 1, 2, 499 or 500 ahead of the client's first one, then five frames
// with commands: the first goes out renumbered to the board's seq + 1, the next ones at + 2 ..
// + 5, each new to the board.
TEST(ProtocolClientRules, ABoardAheadAtStartTakesTheRenumberedFrameAndEveryFrameAfterIt) {
  for (const std::uint16_t first : {std::uint16_t{0}, std::uint16_t{998}}) {
    for (const int ahead : {1, 2, 499, 500}) {
      SCOPED_TRACE(::testing::Message() << "first seq " << first << ", board " << ahead << " ahead");
      Client cl({.first_seq = first});
      for (int k = 0; k < 5; ++k) cl.submit({ap::xy_client::Part::X, {C::Move, 100 + k}}, 0);
      const auto f0 = cl.poll(0, {});
      ASSERT_TRUE(f0);
      const std::uint16_t board_seq = static_cast<std::uint16_t>((first + ahead) % c::kSeqModulo);
      ASSERT_EQ(c::seq_order(board_seq, first), c::SeqOrder::Older);
      auto ev = cl.receive(echo_with_seq(board_seq), 1'000);
      ASSERT_EQ(ev.size(), 1U);
      EXPECT_EQ(ev[0].kind, EchoKind::Resync);
      std::uint16_t last = board_seq;
      for (int k = 0; k < 5; ++k) {
        const auto out = cl.poll(1'000 + k * kPeriodUs, {});
        ASSERT_TRUE(out) << k;
        f::CommandFrame fr;
        ASSERT_TRUE(f::parse_command(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(out->data()), out->size()), fr).ok());
        EXPECT_EQ(fr.seq, (board_seq + 1 + k) % c::kSeqModulo) << k;
        EXPECT_EQ(fr.x, (f::AxisCommand{C::Move, 100 + k})) << k;
        EXPECT_EQ(c::seq_order(last, fr.seq), c::SeqOrder::New) << k;
        last = fr.seq;
        ev = cl.receive(echo_with_seq(fr.seq), 2'000 + k * kPeriodUs);
        ASSERT_EQ(ev.size(), 1U);
        EXPECT_EQ(ev[0].kind, EchoKind::Answer) << k;
      }
      const auto reps = cl.take_reports();
      ASSERT_EQ(reps.size(), 5U);
      for (const auto& r : reps) EXPECT_EQ(r.outcome, Outcome::Done);
    }
  }
}

}  // namespace
