// The delivery client and the board over a lossy link, with the board blocked and unblocked
// at random: every outcome the client reports must say what the board did with the command
// (docs/protocol.md "Outcomes"; the oracle of sim/xy/outcome_oracle.hpp). What the board did is
// the echo model's account of each frame it took (models/xy/echo), which also checks every echo
// the board sends; so a wrong answer (a repeat telling a block of now), a wrong reading of an
// answer in the client, or a frame run twice or never shows here.
//
// Per 1 ms tick: the client polls; what it sends goes down a link that drops, duplicates and
// delays frames; the board ticks; its echoes come back up a link that drops and delays them.
// The user issues random commands of both axes and of the unit (gotos, moves, slow ones, jogs,
// homing, stops, speeds), and the board's environment changes (USB, charger, battery) while
// frames are in flight. After the actions the run settles until the client has nothing left
// in flight.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <deque>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "sim/xy/rig/board_rig.hpp"
#include "models/xy/echo/board_checker.hpp"
#include "pc/xy/client/client.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "sim/xy/rig/rig_sensors.hpp"
#include "sim/xy/outcome_oracle.hpp"

namespace {

namespace em = ap::model::xy_echo;
using ap::sim::xy::Rig;
using C = ap::xy_codec::CommandId;
using Part = ap::xy_client::Part;

struct Submit {
  Part part = Part::X;
  C id = C::Nop;
  std::int32_t data = 0;
};
struct Environment {
  int what = 0;  // 0 usb, 1 charger, 2 battery
  bool on = false;
};
struct Wait {
  int ms = 0;
};
using Action = std::variant<Submit, Environment, Wait>;

rc::Gen<Submit> gen_submit() {
  using rc::gen::element;
  using rc::gen::inRange;
  using rc::gen::just;
  // Positions within the 0..200 mm soft limits mostly, some beyond (refused); data in um.
  const auto axis_cmd = [](Part p) {
    return rc::gen::oneOf(
        rc::gen::build<Submit>(rc::gen::set(&Submit::part, just(p)), rc::gen::set(&Submit::id, element(C::Goto, C::GotoSlow)),
                               rc::gen::set(&Submit::data, inRange<std::int32_t>(0, 260000))),
        rc::gen::build<Submit>(rc::gen::set(&Submit::part, just(p)), rc::gen::set(&Submit::id, element(C::Move, C::MoveSlow)),
                               rc::gen::set(&Submit::data, inRange<std::int32_t>(-60000, 60000))),
        rc::gen::build<Submit>(rc::gen::set(&Submit::part, just(p)), rc::gen::set(&Submit::id, just(C::Jog)),
                               rc::gen::set(&Submit::data, element<std::int32_t>(-2, -1, 0, 1, 2))),
        rc::gen::build<Submit>(rc::gen::set(&Submit::part, just(p)), rc::gen::set(&Submit::id, element(C::Stop, C::Home)),
                               rc::gen::set(&Submit::data, just<std::int32_t>(0))));
  };
  const auto unit_cmd = rc::gen::build<Submit>(
      rc::gen::set(&Submit::part, just(Part::Unit)), rc::gen::set(&Submit::id, element(C::SetFastSpeed, C::SetSlowSpeed, C::SetAccel)),
      rc::gen::set(&Submit::data, inRange<std::int32_t>(1000, 30000)));
  return rc::gen::weightedOneOf<Submit>({{4, axis_cmd(Part::X)}, {4, axis_cmd(Part::Y)}, {1, unit_cmd}});
}

rc::Gen<Action> gen_action() {
  return rc::gen::weightedOneOf<Action>({
      {6, rc::gen::cast<Action>(gen_submit())},
      {2, rc::gen::cast<Action>(rc::gen::build<Environment>(rc::gen::set(&Environment::what, rc::gen::inRange(0, 3)),
                                                            rc::gen::set(&Environment::on, rc::gen::arbitrary<bool>())))},
      {4, rc::gen::cast<Action>(rc::gen::build<Wait>(rc::gen::set(&Wait::ms, rc::gen::inRange(1, 400))))},
  });
}

// One direction of the link: frames dropped, duplicated or delayed (whole frames, so the
// framers' resynchronisation is not what is tested here: properties/xy/protocol does that).
class Link {
 public:
  Link(std::uint32_t seed, int drop_pct, int dup_pct) : rng_(seed), drop_(drop_pct), dup_(dup_pct) {}
  void push(std::int64_t now, const std::string& bytes) {
    if (pct() < drop_) return;
    const int copies = pct() < dup_ ? 2 : 1;
    for (int k = 0; k < copies; ++k) q_.emplace(now + 2 + static_cast<std::int64_t>(rng_() % 12), bytes);
  }
  std::vector<std::string> due(std::int64_t now) {
    std::vector<std::string> out;
    while (!q_.empty() && q_.begin()->first <= now) {
      out.push_back(q_.begin()->second);
      q_.erase(q_.begin());
    }
    return out;
  }

 private:
  int pct() { return static_cast<int>(rng_() % 100); }
  std::mt19937 rng_;
  int drop_, dup_;
  std::multimap<std::int64_t, std::string> q_;  // by delivery time (a later copy may overtake)
};

struct Run {
  Rig rig;
  std::unique_ptr<em::BoardChecker> checker;
  ap::xy_client::Client client;
  Link down, up;
  std::int64_t now_ms = 0;
  std::map<std::uint16_t, em::FrameFate> fates;  // by seq, the last frame taken with it
  std::vector<std::string> bad;
  std::size_t checked = 0, blocked_reports = 0;
  std::array<std::int32_t, 2> jog{};

  Run(std::uint32_t seed, int drop, int dup)
      : client(config()), down(seed, drop, dup), up(seed * 7919U + 1U, drop, 0) {
    rig.in.encoder[0] = {25, 0, 1};  // homed at 50 mm (eq. 7-2, 2 mm lead)
    rig.in.encoder[1] = {25, 0, 1};
    rig.boot();
    checker = std::make_unique<em::BoardChecker>(*rig.board, ap::sim::xy::boot_facts_of(rig));
  }
  static ap::xy_client::Config config() {
    ap::xy_client::Config c;
    c.factory = false;
    return c;
  }

  void tick() {
    const std::int64_t us = now_ms * 1000;
    ap::xy_client::Extras ex;
    ex.jog = jog;
    if (auto out = client.poll(us, ex)) down.push(now_ms, *out);
    for (const std::string& f : down.due(now_ms)) {
      const std::vector<std::uint8_t> b(f.begin(), f.end());
      rig.send_raw(b);
      checker->rx(b);
    }
    const std::size_t before = rig.tx.size();
    rig.tick();
    const std::span<const em::EchoBytes> sent(rig.tx.data() + before, rig.tx.size() - before);
    for (auto& m : checker->after_tick(sent, ap::sim::xy::sensors_of(rig))) note("echo model: " + m);
    if (const auto& f = checker->model().fate_this_tick()) fates[f->frame.seq] = *f;

    for (const auto& e : sent) up.push(now_ms, std::string(e.begin(), e.end()));
    for (const std::string& e : up.due(now_ms)) (void)client.receive(e, us);
    for (const ap::xy_client::Report& r : client.take_reports()) {
      const auto it = r.seq ? fates.find(*r.seq) : fates.end();
      const std::optional<em::FrameFate> fate = it == fates.end() ? std::nullopt : std::optional(it->second);
      ++checked;
      if (r.outcome == ap::xy_client::Outcome::Blocked) ++blocked_reports;
      if (const auto m = ap::sim::xy::check_outcome(r, fate)) note("outcome at " + std::to_string(now_ms) + " ms: " + *m);
    }
    ++now_ms;
  }

  void note(const std::string& m) {
    if (bad.size() < 6) bad.push_back(m);
  }

  std::string log;  // the actions as applied, for the failure message

  void apply(const Action& a) {
    log += std::to_string(now_ms) + " ms: ";
    if (const auto* s = std::get_if<Submit>(&a)) {
      log += std::string(s->part == Part::X ? "x " : s->part == Part::Y ? "y " : "unit ") +
             std::string(ap::xy_codec::kCommands[static_cast<std::size_t>(s->id)].key) + ":" + std::to_string(s->data) + "\n";
    } else if (const auto* e = std::get_if<Environment>(&a)) {
      log += std::string(e->what == 0 ? "usb " : e->what == 1 ? "charger " : "battery low ") + (e->on ? "on\n" : "off\n");
    } else if (const auto* w = std::get_if<Wait>(&a)) {
      log += "wait " + std::to_string(w->ms) + " ms\n";
    }
    if (const auto* s = std::get_if<Submit>(&a)) {
      if (s->id == C::Jog && s->part != Part::Unit) jog[s->part == Part::X ? 0 : 1] = s->data;
      if ((s->id == C::Stop || s->id == C::Goto || s->id == C::Move || s->id == C::GotoSlow || s->id == C::MoveSlow ||
           s->id == C::Home) &&
          s->part != Part::Unit) {
        jog[s->part == Part::X ? 0 : 1] = 0;  // another motion command releases the held key
      }
      (void)client.submit({s->part, {s->id, s->data}}, now_ms * 1000);
      tick();
    } else if (const auto* e = std::get_if<Environment>(&a)) {
      if (e->what == 0) rig.in.usb = e->on;
      if (e->what == 1) rig.in.charger = e->on;
      if (e->what == 2) rig.in.battery_mv = e->on ? 3000 : 4000;  // the 3300 mV default threshold
      tick();
    } else if (const auto* w = std::get_if<Wait>(&a)) {
      for (int k = 0; k < w->ms; ++k) tick();
    }
  }
};

}  // namespace

RC_GTEST_PROP(BoardClientOutcome, EveryReportedOutcomeIsWhatTheBoardDid, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const int drop = *rc::gen::inRange(0, 40);
  const int dup = *rc::gen::inRange(0, 20);
  const auto actions = *rc::gen::container<std::vector<Action>>(gen_action());
  Run run(seed, drop, dup);
  run.apply(Submit{Part::X, C::Goto, 60000});  // at least one command to check
  for (const Action& a : actions) run.apply(a);
  // Settle: the environment clears, the held keys are released, the last frames are answered.
  run.rig.in.usb = run.rig.in.charger = false;
  run.rig.in.battery_mv = 4000;
  run.jog = {};
  for (int k = 0; k < 6000 && (run.client.in_flight_seq() || k < 300); ++k) run.tick();
  if (!run.bad.empty()) {
    std::string all;
    for (const auto& m : run.bad) all += m + "\n";
    RC_FAIL(all + "link: drop " + std::to_string(drop) + " %, duplicate " + std::to_string(dup) + " %\n" + run.log);
  }
  RC_TAG(run.blocked_reports > 0 ? "some reported blocked" : "none blocked");
  RC_ASSERT(run.checked > 0U);
}
