// The simulated PC (docs/sim.md "The simulated PC").
#include "pc.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <thread>
#include <variant>

#include "pc/xy/client/client.hpp"
#include "pc/xy/gcode/program.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/frames.hpp"
#include "core/xy/storage/parameters.hpp"
#include "sim/xy/fault_link.hpp"
#include "sim/xy/outcome_oracle.hpp"
#include "sim/xy/params.hpp"
#include "sim/text.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;
using xy_codec::CommandId;

namespace {

struct AxisPc {
  std::int32_t jog = 0;          // held jog level (sign = direction), 0 = none
  bool jogging = false;          // the last motion command of this axis is a jog
  // The stop check (docs/sim.md "Delivery check"): a confirmed stop must bring the axis to
  // rest within the ramp time, unless a later command for the axis was issued.
  std::optional<std::int64_t> stop_deadline_us;
  std::int64_t stop_issued_us = 0;
  std::optional<std::int64_t> last_motion_issue_us;
  dds::AxisTelemetry prev{};
  bool have_prev = false;
  xy_codec::EchoStatus status = xy_codec::EchoStatus::Idle;
  bool have_status = false;
  std::int32_t data = 0;
};

struct BoardPc {
  std::uint32_t id = 0;
  std::unique_ptr<dds::PcEndpoint> ep;
  std::unique_ptr<xy_client::Client> client;
  std::unique_ptr<FaultLink> down, up;   // to the board, to the PC
  std::array<AxisPc, 2> ax;
  // The delivery check: every frame the client saw answered (their digest, as the board's
  // `probe taken`), the settled commands, and the seq each stop had to go out with.
  std::uint64_t answered_frames = 0;
  std::uint64_t answered_digest = kFnvBasis;
  std::vector<xy_client::Report> reports;
  std::map<xy_client::Ticket, std::uint16_t> stop_seq;
  std::uint32_t timeouts_seen = 0;
  bool gap_open = false;
  dds::Telemetry tel{};
  bool have_tel = false;
  std::map<std::string, std::int32_t> subs;      // subscriber key -> latest data
  std::map<std::uint8_t, std::int32_t> params;   // param index -> latest data
  std::int64_t last_delivered_us = 0;
  std::uint32_t echoes = 0;
  BoardVerdict verdict;
  std::vector<bool> done;   // per expectation: settled (by/at)
  std::uint64_t cmd_seq = 0;
  // The echo check of the PC side (docs/sim.md "Echo checks"): every echo the bus brought
  // from the board, in order (with the FNV-1a digest of that stream), which of them reached
  // the client through the link, and the index of the last one delivered.
  std::vector<Bytes> from_board;
  std::uint64_t from_board_digest = kFnvBasis;
  std::vector<bool> delivered;
  std::optional<std::uint64_t> last_index;
  std::uint32_t link_failures = 0;
  std::uint32_t outcome_failures = 0;
};

struct Mech {
  double um_per_ustep = 2000.0 / 3200.0;
  double fast_um_s = 10'000, slow_um_s = 2000, start_um_s = 500, accel_um_s2 = 20'000, home_um_s = 2000;
  double max_speed_um_s = 10'000;   // the highest speed limit ever requested
  double min_accel_um_s2 = 20'000;
};

std::string status_key(xy_codec::EchoStatus s) {
  const auto* i = xy_codec::find_status(static_cast<std::uint32_t>(s));
  return i != nullptr ? std::string(i->key) : "?";
}

class Pc {
 public:
  Pc(const sc::Scenario& s, const RunOptions& opt, std::uint32_t domain) : s_(s), opt_(opt) {
    pp_ = dds::make_participant(domain);
    for (std::uint32_t b = 0; b < s.boards; ++b) {
      auto pc = std::make_unique<BoardPc>();
      pc->id = b;
      pc->ep = std::make_unique<dds::PcEndpoint>(pp_, b);
      xy_client::Config cc;
      cc.keepalive_us = s.period_us;
      cc.first_seq = s.first_seq;
      cc.factory = true;  // the simulated PC is a developer's tool: it sets the machine up too
      pc->client = std::make_unique<xy_client::Client>(cc);
      pc->down = std::make_unique<FaultLink>(s.faults, sc::Direction::to_board, s.seed * 1'000'003ULL + b * 2ULL);
      pc->up = std::make_unique<FaultLink>(s.faults, sc::Direction::to_pc, s.seed * 1'000'003ULL + b * 2ULL + 1ULL);
      pc->done.assign(s.expectations.size(), false);
      pc->verdict.board = b;
      boards_.push_back(std::move(pc));
    }
    // Mechanics the PC assumes (defaults + setup), for unit conversion of the telemetry.
    const xy_storage::ParameterSet d = xy_storage::defaults();
    double lead = d.lead_pitch_um, steps = d.steps_per_rev, micro = d.microsteps;
    mech_.fast_um_s = d.fast_speed_um_s;
    mech_.slow_um_s = d.slow_speed_um_s;
    mech_.start_um_s = d.start_speed_um_s;
    mech_.accel_um_s2 = d.max_acceleration_um_s2;
    mech_.home_um_s = d.homing_speed_um_s;
    for (const sc::Setup& st : s.setup) {
      if ((st.key == "param" || st.key == "fram") && st.amount) {
        const auto id = param_by_name(st.word);
        if (id == xy_storage::ParamId::LeadPitch) lead = st.amount->value;
        if (id == xy_storage::ParamId::StepsPerRev) steps = st.amount->value;
        if (id == xy_storage::ParamId::Microsteps) micro = st.amount->value;
        if (id == xy_storage::ParamId::FastSpeed) mech_.fast_um_s = st.amount->value;
        if (id == xy_storage::ParamId::MaxAcceleration) mech_.accel_um_s2 = st.amount->value;
      }
    }
    mech_.um_per_ustep = lead / (steps * micro);
    mech_.max_speed_um_s = std::max({mech_.fast_um_s, mech_.slow_um_s, mech_.home_um_s});
    mech_.min_accel_um_s2 = mech_.accel_um_s2;
    // Which parameters the echoes must carry (param.NAME expectations), in slot 3.
    for (const sc::Expectation& e : s.expectations) {
      if (e.subject.rfind("param.", 0) == 0) {
        const auto id = param_by_name(e.subject.substr(6));
        if (!id) throw std::runtime_error("unknown parameter in expectation: " + e.subject);
        const auto idx = static_cast<std::uint8_t>(*id);
        if (std::find(param_slots_.begin(), param_slots_.end(), idx) == param_slots_.end()) param_slots_.push_back(idx);
      }
    }
  }

  ~Pc() {
    boards_.clear();
    pp_.reset();
  }

  void connect() {
    for (auto& b : boards_) {
      if (!b->ep->wait_matched(std::chrono::seconds(20))) {
        throw std::runtime_error("board " + std::to_string(b->id) + " did not appear on the bus within 20 s");
      }
    }
  }

  RunResult run() {
    const auto wall0 = std::chrono::steady_clock::now();
    connect();
    setup();
    std::size_t next_action = 0;
    std::int64_t t = 0;
    for (; t <= s_.duration_us; t += opt_.step_us) {
      if (opt_.realtime) std::this_thread::sleep_until(wall0 + std::chrono::microseconds(t));
      while (next_action < s_.actions.size() && s_.actions[next_action].t_us <= t) {
        apply(s_.actions[next_action], t);
        ++next_action;
      }
      step(t);
      for (auto& b : boards_) {
        check_safety(*b, t);
        evaluate(*b, t, false);
      }
    }
    t -= opt_.step_us;
    for (auto& b : boards_) evaluate(*b, t, true);
    finish(t);
    RunResult r;
    r.failures = failures_;
    r.pass = failures_.empty();
    r.vtime_us = t;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    r.bus_round_trips = round_trips_;
    r.domain = pp_->domain();
    for (auto& b : boards_) r.boards.push_back(b->verdict);
    return r;
  }

 private:
  void fail(const std::string& m) {
    if (failures_.size() < 200) failures_.push_back(m);
  }

  std::string env(BoardPc& b, const std::string& line, std::int64_t t) {
    const std::vector<std::uint8_t> bytes(line.begin(), line.end());
    const std::uint64_t seq = b.ep->send(bytes, static_cast<std::uint64_t>(t), kFlagEnv);
    ++round_trips_;
    const dds::EchoSample e = wait_echo(b, seq);
    std::string reply(e.bytes.begin(), e.bytes.end());
    if (reply.rfind("ok", 0) != 0) fail("board " + std::to_string(b.id) + ": environment command '" + line + "': " + reply);
    return reply.size() > 3 ? reply.substr(3) : std::string();
  }

  dds::EchoSample wait_echo(BoardPc& b, std::uint64_t seq) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    for (;;) {
      auto e = b.ep->take_echo(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()));
      if (!e) throw std::runtime_error("board " + std::to_string(b.id) + " did not answer bus command " + std::to_string(seq));
      if (e->cmd_seq == seq) return std::move(*e);
    }
  }

  void setup() {
    for (auto& b : boards_) {
      for (const sc::Setup& st : s_.setup) {
        const auto v = [&] { return std::to_string(std::llround(st.amount ? st.amount->value : 0.0)); };
        if (st.key == "battery") env(*b, "battery " + v(), 0);
        else if (st.key == "charger" || st.key == "usb") env(*b, st.key + (st.word == "plugged" ? " 1" : " 0"), 0);
        else if (st.key == "ble") env(*b, "ble " + st.word, 0);
        else if (st.key == "encoder") env(*b, "encoder " + st.word, 0);
        else if (st.key == "temperature") env(*b, "temperature " + v(), 0);
        else if (st.key == "pos") env(*b, std::string("pos ") + st.axis + " " + v(), 0);
        else if (st.key == "endstop") env(*b, std::string("endstop_at ") + st.axis + " " + st.word + " " + v(), 0);
        else env(*b, st.key + " " + st.word + " " + v(), 0);   // param / fram
      }
      env(*b, "boot", 0);
    }
  }

  // The program of a `gcode` action: the path as written, else from the source tree.
  xy_pcgcode::Program load_gcode(const sc::Action& a, const std::string& where) {
    std::string path = a.word;
    if (!std::filesystem::is_regular_file(path)) path = std::string(AP_SOURCE_DIR) + "/" + a.word;
    std::ifstream in(path);
    if (!in) {
      fail(where + ": cannot read G-code file " + a.word);
      return {};
    }
    std::ostringstream text;
    text << in.rdbuf();
    xy_pcgcode::Options o;
    o.dialect = a.word2 == "thesis" ? xy_gcode::Dialect::Thesis : xy_gcode::Dialect::Tolerant;
    try {
      xy_pcgcode::Program p = xy_pcgcode::translate(text.str(), o, a.word);
      // The board queues 16 segments (docs/cnc.md "Refusals"); the simulated PC sends a program
      // at once, so a longer one would meet QueueFull.
      if (p.segment_frames > 16) {
        fail(where + ": " + a.word + " has more than 16 XY segments (the board's queue)");
        return {};
      }
      return p;
    } catch (const xy_pcgcode::ProgramError& e) {
      fail(where + ": " + e.what());
    }
    return {};
  }

  static std::int32_t um(const sc::Action& a) { return static_cast<std::int32_t>(std::llround(a.amount ? a.amount->value : 0.0)); }

  // A user command goes to the client, which delivers it exactly once or reports why not.
  void submit(BoardPc& b, xy_client::Part part, CommandId id, std::int32_t data, std::int64_t t) {
    const xy_client::Command c{part, {id, data}};
    const std::uint16_t next = b.client->next_seq();
    const xy_client::Ticket tk = b.client->submit(c, t);
    // A stop must leave in the next new frame (docs/protocol.md "Delivery"): behind at most
    // the frame already in flight, never behind anything queued.
    if (id == CommandId::Stop && part != xy_client::Part::Unit) b.stop_seq[tk] = next;
    if (part != xy_client::Part::Unit) {
      AxisPc& x = b.ax[part == xy_client::Part::Y ? 1 : 0];
      if (id != CommandId::Stop) x.last_motion_issue_us = t;
    }
  }

  void release_and_submit(BoardPc& b, AxisPc& x, xy_client::Part part, CommandId id, std::int32_t data, std::int64_t t) {
    x.jog = 0;
    x.jogging = false;
    submit(b, part, id, data, t);
  }

  void apply(const sc::Action& a, std::int64_t t) {
    for (auto& bp : boards_) {
      BoardPc& b = *bp;
      if (!a.target.all && a.target.board != b.id) continue;
      const std::size_t ai = a.axis == 'y' ? 1 : 0;
      const xy_client::Part part = ai == 1 ? xy_client::Part::Y : xy_client::Part::X;
      AxisPc& x = b.ax[ai];
      const std::string where = s_.name + ".scn:" + std::to_string(a.line);
      switch (a.verb) {
        case sc::Verb::jog:
          // The jog is a command like any other; the held level then rides in every new frame.
          x.jog = (a.word == "-" ? -1 : 1) * (a.word2 == "fast" ? xy_codec::kJogFast : xy_codec::kJogSlow);
          x.jogging = true;
          submit(b, part, CommandId::Jog, x.jog, t);
          break;
        // Any other command of the axis releases the held key.
        case sc::Verb::stop: release_and_submit(b, x, part, CommandId::Stop, 0, t); break;
        case sc::Verb::go_to:
          release_and_submit(b, x, part, a.word2 == "slow" ? CommandId::GotoSlow : CommandId::Goto, um(a), t);
          break;
        case sc::Verb::move:
          release_and_submit(b, x, part, a.word2 == "slow" ? CommandId::MoveSlow : CommandId::Move, um(a), t);
          break;
        case sc::Verb::home: release_and_submit(b, x, part, CommandId::Home, 0, t); break;
        case sc::Verb::set_speed:
          submit(b, xy_client::Part::Unit, a.word == "fast" ? CommandId::SetFastSpeed : CommandId::SetSlowSpeed, um(a), t);
          if (a.word == "fast") mech_.fast_um_s = um(a);
          mech_.max_speed_um_s = std::max(mech_.max_speed_um_s, static_cast<double>(um(a)));
          break;
        case sc::Verb::set_accel:
          submit(b, xy_client::Part::Unit, CommandId::SetAccel, um(a), t);
          mech_.accel_um_s2 = um(a);
          mech_.min_accel_um_s2 = std::min(mech_.min_accel_um_s2, static_cast<double>(um(a)));
          break;
        case sc::Verb::save: submit(b, xy_client::Part::Unit, CommandId::SaveParams, 0, t); break;
        case sc::Verb::peripherals:
          submit(b, xy_client::Part::Unit, a.word == "on" ? CommandId::PeriphOn : CommandId::PeriphOff, 0, t);
          break;
        case sc::Verb::tmc:
          if (a.word == "IRUN" || a.word == "IHOLD") {
            submit(b, part, a.word == "IRUN" ? CommandId::SetIrun : CommandId::SetIhold, um(a), t);
          } else {
            fail(where + ": tmc " + a.word + " cannot be set over the protocol (only IRUN and IHOLD have commands)");
          }
          break;
        case sc::Verb::subscribe:
        case sc::Verb::unsubscribe: {
          std::vector<xy_codec::SubscriberId> ids;
          if (a.word == "battery" || a.word == "all") ids.push_back(xy_codec::SubscriberId::BatteryMv);
          if (a.word == "charge_current" || a.word == "all") ids.push_back(xy_codec::SubscriberId::ChargeMa);
          if (a.word == "temperature" || a.word == "all") ids.push_back(xy_codec::SubscriberId::TemperatureMc);
          if (a.word == "rotation" || a.word == "all") ids.push_back(xy_codec::SubscriberId::RotationMdeg);
          for (const auto id : ids) {
            const auto it = std::find(subscribed_.begin(), subscribed_.end(), id);
            if (a.verb == sc::Verb::subscribe && it == subscribed_.end()) subscribed_.push_back(id);
            if (a.verb == sc::Verb::unsubscribe && it != subscribed_.end()) subscribed_.erase(it);
          }
          break;
        }
        case sc::Verb::gcode: {
          // docs/cnc.md: the PC parses the program and sends it as path frames; the two parts of
          // each frame go to the client back to back, so they leave in one frame.
          const xy_pcgcode::Program prog = load_gcode(a, where);
          for (const xy_pcgcode::Frame& f : prog.frames) {
            if (f.y_id == CommandId::Nop) {
              submit(b, xy_client::Part::Unit, f.x_id, f.x, t);
            } else {
              submit(b, xy_client::Part::X, f.x_id, f.x, t);
              submit(b, xy_client::Part::Y, f.y_id, f.y, t);
            }
          }
          break;
        }
        case sc::Verb::raw: {
          const Bytes bytes(a.word.begin(), a.word.end());
          b.down->push(t, bytes, b.verdict.to_board);
          break;
        }
        case sc::Verb::link_cut: {
          const std::int64_t until = a.amount ? t + static_cast<std::int64_t>(a.amount->value) : s_.duration_us + 1;
          b.down->cut_until(until);
          b.up->cut_until(until);
          break;
        }
        case sc::Verb::link_restore:
          b.down->cut_until(-1);
          b.up->cut_until(-1);
          break;
        case sc::Verb::charger: env(b, std::string("charger ") + (a.word == "plug" ? "1" : "0"), t); break;
        case sc::Verb::usb: env(b, std::string("usb ") + (a.word == "plug" ? "1" : "0"), t); break;
        case sc::Verb::battery: env(b, "battery " + std::to_string(um(a)), t); break;
        case sc::Verb::temperature: env(b, "temperature " + std::to_string(um(a)), t); break;
        case sc::Verb::rotate: env(b, "rotate " + std::to_string(um(a)), t); break;
        case sc::Verb::ble: env(b, "ble " + a.word, t); break;
        case sc::Verb::endstop: env(b, std::string("endstop ") + a.axis + " " + a.word + " " + a.word2, t); break;
        case sc::Verb::button: env(b, "button " + a.word, t); break;
        case sc::Verb::reboot:
          env(b, "reboot", t);
          break;
      }
    }
  }

  // What rides in every new frame: the held jog levels and the subscriber slots.
  xy_client::Extras extras(BoardPc& b) {
    xy_client::Extras e;
    for (std::size_t i = 0; i < 2; ++i) e.jog[i] = b.ax[i].jog;
    std::size_t slot = 0;
    for (const auto id : subscribed_) {
      if (slot >= (param_slots_.empty() ? xy_codec::kSubscriberSlots : xy_codec::kSubscriberSlots - 1)) break;
      e.subs[slot++] = {id, 0};
    }
    if (!param_slots_.empty()) {
      const std::uint32_t n = b.client->counters().new_frames;
      e.subs[xy_codec::kSubscriberSlots - 1] = {xy_codec::SubscriberId::Param, param_slots_[n % param_slots_.size()]};
    }
    return e;
  }

  void step(std::int64_t t) {
    for (auto& bp : boards_) {
      BoardPc& b = *bp;
      if (const auto text = b.client->poll(t, extras(b))) {
        b.down->push(t, Bytes(text->begin(), text->end()), b.verdict.to_board);
      }
      const Bytes out = b.down->pop(t, 3 * xy_codec::kCommandLength, b.verdict.to_board);
      if (!out.empty()) {
        const bool session = b.have_tel ? b.tel.ble_status == 2 : true;
        bool ok_frame = session;
        for (std::size_t k = 0; ok_frame && k + xy_codec::kCommandLength <= out.size(); k += xy_codec::kCommandLength) {
          xy_frame::CommandFrame cf;
          ok_frame = xy_frame::parse_command(std::span<const std::uint8_t>(out.data() + k, xy_codec::kCommandLength), cf).ok();
        }
        if (ok_frame) b.last_delivered_us = t;
      }
      b.cmd_seq = b.ep->send(out, static_cast<std::uint64_t>(t));
      ++round_trips_;
    }
    for (auto& bp : boards_) {
      BoardPc& b = *bp;
      const dds::EchoSample e = wait_echo(b, b.cmd_seq);
      if (!b.have_tel || e.telemetry != b.tel) {
        for (std::size_t i = 0; i < 2; ++i) {
          b.ax[i].prev = b.have_tel ? b.tel.axis[i] : e.telemetry.axis[i];
          b.ax[i].have_prev = b.have_tel;
        }
      }
      b.tel = e.telemetry;
      b.have_tel = true;
      if (e.bytes.size() % xy_codec::kEchoLength != 0) {
        fail("echo check: board " + std::to_string(b.id) + " at " + tstr(t) + ": the bus brought " +
             std::to_string(e.bytes.size()) + " TX bytes, not whole echoes");
      }
      for (std::size_t k = 0; k + xy_codec::kEchoLength <= e.bytes.size(); k += xy_codec::kEchoLength) {
        Bytes echo(e.bytes.begin() + static_cast<std::ptrdiff_t>(k),
                   e.bytes.begin() + static_cast<std::ptrdiff_t>(k + xy_codec::kEchoLength));
        b.from_board_digest = fnv1a(b.from_board_digest, echo);
        b.from_board.push_back(echo);
        b.delivered.push_back(false);
        b.up->push(t, std::move(echo), b.verdict.to_pc, b.from_board.size() - 1);
      }
      std::vector<FrameTag> tags;
      const Bytes in = b.up->pop(t, 64 * xy_codec::kEchoLength, b.verdict.to_pc, &tags);
      check_delivered(b, in, tags, t);
      if (!in.empty()) receive(b, in, t);
      settle(b, t);
    }
  }

  // ---- the delivery check (docs/sim.md "Delivery check") ---------------------------------
  void settle(BoardPc& b, std::int64_t t) {
    // A gap is a run of retransmission timeouts with no answer in between.
    const std::uint32_t timeouts = b.client->counters().timeouts;
    if (timeouts > b.timeouts_seen) {
      if (b.gap_open && !b.verdict.gaps.empty()) {
        b.verdict.gaps.back().lost += timeouts - b.timeouts_seen;
      } else {
        b.verdict.gaps.push_back({t, timeouts - b.timeouts_seen});
      }
      b.gap_open = true;
    }
    b.timeouts_seen = timeouts;
    const double stop_s = mech_.max_speed_um_s / std::max(1.0, mech_.min_accel_um_s2);
    for (xy_client::Report& r : b.client->take_reports()) {
      const auto it = b.stop_seq.find(r.ticket);
      if (it != b.stop_seq.end()) {
        const std::size_t i = r.command.part == xy_client::Part::Y ? 1 : 0;
        if (r.seq && *r.seq != it->second && b.client->counters().resyncs == 0) {
          fail("delivery: board " + std::to_string(b.id) + ": the stop of axis " + (i == 0 ? "x" : "y") + " issued at " +
               tstr(r.issued_us) + " went out in frame " + std::to_string(*r.seq) + ", not in the next new frame (" +
               std::to_string(it->second) + ")");
        }
        if (r.outcome == xy_client::Outcome::Done) {
          b.ax[i].stop_deadline_us = t + static_cast<std::int64_t>(stop_s * 1e6) + 2 * opt_.step_us;
          b.ax[i].stop_issued_us = r.issued_us;
        }
        b.stop_seq.erase(it);
      }
      check_outcome(b, r, t);
      b.reports.push_back(r);
    }
    for (std::size_t i = 0; i < 2; ++i) {
      AxisPc& x = b.ax[i];
      if (!x.stop_deadline_us || t < *x.stop_deadline_us) continue;
      const bool later_command = x.last_motion_issue_us && *x.last_motion_issue_us >= x.stop_issued_us;
      if (!later_command && b.tel.axis[i].speed != 0) {
        fail("delivery: board " + std::to_string(b.id) + " axis " + (i == 0 ? "x" : "y") + " still moves at " + tstr(t) +
             ", a ramp time after its stop was confirmed");
      }
      x.stop_deadline_us.reset();
    }
  }

  // The outcome check (docs/sim.md "Outcome check"): the outcome the user is told against what
  // the board did with the frame, as the board-side echo model states it. A disagreement fails
  // the run like a safety violation.
  void check_outcome(BoardPc& b, const xy_client::Report& r, std::int64_t t) {
    std::optional<model::xy_echo::FrameFate> fate;
    if (xy_client::delivered(r.outcome) && r.seq) {  // done, refused, blocked: a frame answered it
      const std::string text = env(b, "probe fate." + std::to_string(*r.seq), t);
      if (text != "none") {
        fate = parse_fate(text);
        if (!fate) {
          fail("outcome: board " + std::to_string(b.id) + ": unreadable fate '" + text + "'");
          return;
        }
      }
    }
    ++b.verdict.delivery.outcomes_checked;
    if (const auto m = ap::sim::xy::check_outcome(r, fate)) {
      if (++b.outcome_failures <= 5) fail("outcome: board " + std::to_string(b.id) + " at " + tstr(t) + ": " + *m);
    }
  }

  // ---- the echoes that reached the client are ones the board sent, in order -------------
  void check_delivered(BoardPc& b, const Bytes& in, const std::vector<FrameTag>& tags, std::int64_t t) {
    auto bad = [&](const std::string& what) {
      if (++b.link_failures <= 5) fail("echo check: board " + std::to_string(b.id) + " at " + tstr(t) + ": " + what);
    };
    if (in.size() != tags.size() * xy_codec::kEchoLength) {
      bad(std::to_string(in.size()) + " bytes left the link for " + std::to_string(tags.size()) + " echoes");
      return;
    }
    for (std::size_t k = 0; k < tags.size(); ++k) {
      const FrameTag& g = tags[k];
      const std::string n = "echo #" + std::to_string(g.index);
      if (g.index >= b.from_board.size()) {
        bad(n + " left the link but the board never sent it");
        continue;
      }
      const Bytes& sent = b.from_board[g.index];
      std::size_t differ = 0;
      for (std::size_t i = 0; i < xy_codec::kEchoLength; ++i) differ += in[k * xy_codec::kEchoLength + i] != sent[i] ? 1U : 0U;
      // Not corrupted: byte-identical. Corrupted on purpose: one byte per corruption (two
      // corruptions may hit the same byte, and only then can masks cancel).
      if (g.corruptions == 0 && differ != 0) bad(n + " differs from what the board sent in " + std::to_string(differ) + " bytes");
      if (g.corruptions == 1 && differ != 1) bad(n + " corrupted once by the link but differs in " + std::to_string(differ) + " bytes");
      if (g.corruptions > 1 && differ > g.corruptions) bad(n + " differs in more bytes than the link corrupted");
      // Order: each echo after the last one delivered, except the second copy of a duplicate
      // (the same one again) and a frame the link held back on purpose (reordered).
      if (b.last_index && g.index <= *b.last_index && !(g.duplicate && g.index == *b.last_index) && !g.reordered) {
        bad(n + " arrived after echo #" + std::to_string(*b.last_index) + " (out of order, no reorder or duplicate fault)");
      }
      if (!g.reordered && (!b.last_index || g.index > *b.last_index)) b.last_index = g.index;
      b.delivered[g.index] = true;
    }
  }

  void receive(BoardPc& b, const Bytes& in, std::int64_t t) {
    for (const xy_client::EchoEvent& ev : b.client->receive(std::span<const std::uint8_t>(in), t)) {
      if (ev.kind == xy_client::EchoKind::Answer) {
        ++b.answered_frames;
        b.gap_open = false;
        if (const auto bytes = xy_client::format(ev.answered)) {
          b.answered_digest = fnv1a(b.answered_digest, std::span<const std::uint8_t>(
                                                           reinterpret_cast<const std::uint8_t*>(bytes->data()), bytes->size()));
        }
      }
      // A rejection echo answers a damaged frame, not the axes: the status shown stays the
      // last one the board reported.
      if (ev.kind == xy_client::EchoKind::Answer || ev.kind == xy_client::EchoKind::Late || ev.kind == xy_client::EchoKind::Resync) {
        ++b.echoes;
        for (std::size_t i = 0; i < 2; ++i) {
          const xy_frame::AxisEcho& ae = i == 0 ? ev.echo.x : ev.echo.y;
          b.ax[i].status = ae.status;
          b.ax[i].data = ae.data;
          b.ax[i].have_status = true;
        }
        for (const xy_frame::SubscriberPacket& p : ev.echo.subs) {
          if (p.slot.id == xy_codec::SubscriberId::None) continue;
          if (p.slot.id == xy_codec::SubscriberId::Param) {
            b.params[p.slot.arg] = p.data;
          } else {
            const auto* info = xy_codec::find_subscriber(static_cast<std::uint32_t>(p.slot.id));
            if (info != nullptr) b.subs[std::string(info->key)] = p.data;
          }
        }
      }
    }
  }

  // ---- the axis safety properties on the telemetry (every step) --------------------------
  void check_safety(BoardPc& b, std::int64_t t) {
    const double dt = static_cast<double>(opt_.step_us) / 1e6;
    for (std::size_t i = 0; i < 2; ++i) {
      const AxisPc& x = b.ax[i];
      const dds::AxisTelemetry& n = b.tel.axis[i];
      const char an = i == 0 ? 'x' : 'y';
      auto bad = [&](const std::string& what) {
        fail("safety: board " + std::to_string(b.id) + " axis " + an + " at " + tstr(t) + ": " + what);
      };
      const double v = n.speed * mech_.um_per_ustep;
      if (v > mech_.max_speed_um_s * 1.01 + 2 * mech_.um_per_ustep) {
        bad("speed " + fmt(v) + " um/s above every speed limit the PC set (" + fmt(mech_.max_speed_um_s) + " um/s)");
      }
      if (!x.have_prev) continue;
      const dds::AxisTelemetry& p = x.prev;
      if (p.endstop_max && n.endstop_max && n.pos > p.pos) bad("moved toward the active max endstop");
      if (p.endstop_min && n.endstop_min && n.pos < p.pos) bad("moved toward the active min endstop");
      if (p.blocked && n.blocked && n.speed > p.speed) bad("speed increased while the board is blocked");
      if (n.dir != p.dir) {
        const double vp = p.speed * mech_.um_per_ustep;
        const double bound = mech_.start_um_s + 2.0 * mech_.accel_um_s2 * dt + 2 * mech_.um_per_ustep;
        if (vp > bound) bad("DIR reversed while moving at " + fmt(vp) + " um/s (start speed " + fmt(mech_.start_um_s) + ")");
      }
      // The link watchdog: 3 command periods without a frame reaching the board, then a ramped
      // stop from at most the highest speed at the lowest acceleration ever set.
      const double stop_s = mech_.max_speed_um_s / std::max(1.0, mech_.min_accel_um_s2);
      const auto bound_us = static_cast<std::int64_t>(3 * s_.period_us + static_cast<std::int64_t>(stop_s * 1e6) + 2 * opt_.step_us);
      if (x.jogging && t - b.last_delivered_us > bound_us && n.speed != 0) {
        bad("still jogging " + tstr(t - b.last_delivered_us) + " after the last frame reached the board");
      }
    }
  }

  // ---- expectations ----------------------------------------------------------------------
  using Val = std::variant<std::string, double>;

  std::optional<Val> value(BoardPc& b, const std::string& subj, std::int64_t t) {
    auto on = [](bool v) { return Val(std::string(v ? "on" : "off")); };
    if (subj.size() > 2 && (subj[0] == 'x' || subj[0] == 'y') && subj[1] == '.') {
      const std::size_t i = subj[0] == 'y' ? 1 : 0;
      const std::string f = subj.substr(2);
      const dds::AxisTelemetry& a = b.tel.axis[i];
      if (f == "pos") return Val(a.pos * mech_.um_per_ustep);
      if (f == "target") return Val(a.target * mech_.um_per_ustep);
      if (f == "speed") return Val(a.speed * mech_.um_per_ustep);
      if (f == "dir") return Val(std::string(a.dir != 0 ? "+" : "-"));
      if (f == "endstop_min") return on(a.endstop_min);
      if (f == "endstop_max") return on(a.endstop_max);
      if (f == "enabled") return on(a.enabled);
      if (f == "blocked") return on(a.blocked);
      if (f == "status") return Val(b.ax[i].have_status ? status_key(b.ax[i].status) : std::string("none"));
      if (f == "lost_steps") return Val(std::stod(env(b, "probe " + subj, t)));
      return std::nullopt;
    }
    if (subj.rfind("board.", 0) == 0) {
      const std::string f = subj.substr(6);
      if (f == "state") {
        static const char* kStates[] = {"blocked", "user", "param"};
        return Val(std::string(b.tel.main_state < 3 ? kStates[b.tel.main_state] : "?"));
      }
      if (f == "led") return Val(led_word(b.tel.led));
      if (f == "ble") {
        // Tab. 7-2 by (S1 | S2 << 1): (0,0) connected, (1,0) standby, (0,1) session, (1,1) shutdown.
        static const char* kBle[] = {"connected", "standby", "session", "shutdown"};
        return Val(std::string(kBle[b.tel.ble_status & 3U]));
      }
      if (f == "charger") return on(b.tel.charger);
      if (f == "usb") return on(b.tel.usb);
      if (f == "low_battery") return on(b.tel.low_battery);
      if (f == "battery") return Val(static_cast<double>(b.tel.battery_mv));
      if (f == "charge_current") return Val(static_cast<double>(b.tel.charge_ma));
      if (f == "temperature") return Val(static_cast<double>(b.tel.temperature_mc));
      if (f == "rotation") return Val(static_cast<double>(b.tel.rotation_mdeg));
      return std::nullopt;
    }
    if (subj.rfind("param.", 0) == 0) {
      const auto id = param_by_name(subj.substr(6));
      const auto it = id ? b.params.find(static_cast<std::uint8_t>(*id)) : b.params.end();
      if (it == b.params.end()) return Val(std::string("none"));
      return Val(static_cast<double>(it->second));
    }
    if (subj.rfind("sub.", 0) == 0) {
      std::string k = subj.substr(4);
      if (k == "charge_current") k = "charge";
      if (k == "temperature") k = "temp";
      const auto it = b.subs.find(k);
      if (it == b.subs.end()) return Val(std::string("none"));
      return Val(static_cast<double>(it->second));
    }
    if (subj == "echo.count") return Val(static_cast<double>(b.echoes));
    if (subj == "echo.x.id" || subj == "echo.y.id") return Val(static_cast<double>(b.ax[subj[5] == 'y' ? 1 : 0].status));
    if (subj == "echo.x.data" || subj == "echo.y.data") return Val(static_cast<double>(b.ax[subj[5] == 'y' ? 1 : 0].data));
    if (subj.rfind("tmc.", 0) == 0 || subj.rfind("fram.", 0) == 0 || subj == "watchdog_stops" || subj == "lost_steps") {
      return Val(std::stod(env(b, "probe " + subj, t)));
    }
    const xy_client::ClientCounters& c = b.client->counters();
    if (subj == "gaps") return Val(static_cast<double>(c.timeouts));
    if (subj == "rejected") return Val(static_cast<double>(c.rejected));
    if (subj == "commands") return Val(static_cast<double>(c.sent));
    if (subj == "echoes") return Val(static_cast<double>(c.answered));
    if (subj == "delivered") return Val(static_cast<double>(c.delivered));
    if (subj == "failed") return Val(static_cast<double>(c.failed));
    if (subj == "retransmissions") return Val(static_cast<double>(c.retransmissions));
    if (subj.rfind("outcome.", 0) == 0) {
      const std::string key = subj.substr(8);
      return Val(static_cast<double>(std::count_if(b.reports.begin(), b.reports.end(),
                                                   [&](const xy_client::Report& r) { return key == xy_client::to_string(r.outcome); })));
    }
    return std::nullopt;
  }

  // The scenario language's own comparison (sim/xy/scenario.hpp), on the value with the
  // subject's dimension; a word where a number is due (or the reverse) is a failure of the
  // expectation, not of the run.
  static bool compare(const Val& got, const sc::Expectation& e, std::string* why) {
    sc::Value v;
    if (const auto* d = std::get_if<double>(&got)) {
      const auto* want = std::get_if<sc::Quantity>(&e.value);
      v = sc::Quantity{*d, sc::subject_dim(e.subject).value_or(want != nullptr ? want->dim : sc::Dim::none)};
    } else {
      v = std::get<std::string>(got);
    }
    try {
      return sc::holds(e, v);
    } catch (const std::invalid_argument& x) {
      *why = x.what();
      return false;
    }
  }

  static std::string show(const Val& v, const sc::Expectation& e) {
    if (const auto* s = std::get_if<std::string>(&v)) return *s;
    const double d = std::get<double>(v);
    if (const auto* q = std::get_if<sc::Quantity>(&e.value)) {
      const std::string u(sc::unit_name(q->dim));
      return fmt(d) + (u.empty() ? "" : " " + u);
    }
    return fmt(d);
  }

  std::string describe(const sc::Expectation& e, std::uint32_t board) {
    sc::Scenario one;
    one.name = "x";
    one.duration_us = 1;
    one.expectations.push_back(e);
    std::string text = sc::to_text(one);
    const std::size_t p = text.find("expect ");
    text = p == std::string::npos ? e.subject : text.substr(p);
    while (!text.empty() && text.back() == '\n') text.pop_back();
    return s_.name + ".scn:" + std::to_string(e.line) + ": board " + std::to_string(board) + ": " + text;
  }

  void evaluate(BoardPc& b, std::int64_t t, bool at_end) {
    for (std::size_t k = 0; k < s_.expectations.size(); ++k) {
      const sc::Expectation& e = s_.expectations[k];
      if (!e.target.all && e.target.board != b.id) continue;
      if (b.done[k]) continue;
      bool check = false;
      switch (e.when) {
        case sc::When::at: check = !at_end && t >= e.t_us; break;
        case sc::When::always: check = !at_end; break;
        case sc::When::between: check = !at_end && t >= e.t_us && t <= e.t2_us; break;
        case sc::When::by: check = !at_end && t <= e.t_us + opt_.step_us - 1; break;
        case sc::When::end: check = at_end; break;
      }
      if (at_end && e.when == sc::When::by && !b.done[k]) {
        fail(describe(e, b.id) + ": never held");
        b.done[k] = true;
        continue;
      }
      if (!check) {
        if (e.when == sc::When::by && t > e.t_us && !b.done[k]) {
          fail(describe(e, b.id) + ": did not hold by " + tstr(e.t_us) + " (last value " + last_[k] + ")");
          b.done[k] = true;
        }
        continue;
      }
      const std::optional<Val> v = value(b, e.subject, t);
      if (!v) {
        fail(describe(e, b.id) + ": subject not available in the simulated PC");
        b.done[k] = true;
        continue;
      }
      std::string why;
      const bool ok = compare(*v, e, &why);
      last_[k] = show(*v, e) + (why.empty() ? "" : " (" + why + ")");
      switch (e.when) {
        case sc::When::at:
        case sc::When::end:
          b.done[k] = true;
          if (!ok) fail(describe(e, b.id) + ": got " + last_[k] + " at " + tstr(t));
          break;
        case sc::When::by:
          if (ok) b.done[k] = true;
          break;
        case sc::When::always:
        case sc::When::between:
          if (!ok) {
            fail(describe(e, b.id) + ": got " + last_[k] + " at " + tstr(t));
            b.done[k] = true;   // report the first violation only
          }
          break;
      }
    }
  }

  void finish(std::int64_t t) {
    for (auto& bp : boards_) {
      BoardPc& b = *bp;
      const std::string viol = env(b, "probe violations", t);
      if (!viol.empty() && viol[0] != '0') fail("safety (board-side monitor, every tick): board " + std::to_string(b.id) + ": " + viol);
      b.verdict.lost_step_risks = static_cast<std::uint64_t>(std::stoull(env(b, "probe lost_steps", t)));
      finish_echo_checks(b, t);
      // The client's counters, as the verdict reports them.
      const xy_client::ClientCounters& c = b.client->counters();
      BoardVerdict& v = b.verdict;
      v.commands = c.sent;
      v.echoes = c.answered;
      v.lost = c.timeouts;
      v.rejected = c.rejected;
      v.malformed = c.malformed;
      v.unexpected = c.resyncs;
      v.duplicates = c.late;
      v.delivery.submitted = c.commands;
      v.delivery.delivered = c.delivered;
      v.delivery.failed = c.failed;
      v.delivery.frames_answered = b.answered_frames;
      v.delivery.given_up = c.given_up;
      v.delivery.retransmissions = c.retransmissions;
      v.delivery.new_frames = c.new_frames;
      v.delivery.reports = b.reports;
      finish_delivery_check(b, t);
    }
    for (auto& bp : boards_) {
      const std::uint64_t seq = bp->ep->send({}, static_cast<std::uint64_t>(t), dds::kFlagShutdown);
      (void)wait_echo(*bp, seq);
    }
  }

  // Exactly once, in order (docs/sim.md "Delivery check"): the frames the board took are the
  // frames the client saw answered, one for one and in the same order, unless a frame ran out of
  // transmissions (its fate is unknown: at most once) or a raw frame went around the client.
  void finish_delivery_check(BoardPc& b, std::int64_t t) {
    const std::string who = "delivery: board " + std::to_string(b.id);
    const xy_client::ClientCounters& c = b.client->counters();
    BoardVerdict& v = b.verdict;
    std::istringstream in(env(b, "probe taken", t));
    std::uint64_t taken = 0, digest = 0;
    if (!(in >> taken >> digest)) {
      fail(who + ": no answer to probe taken");
      return;
    }
    v.delivery.frames_taken = taken;
    const bool raw = std::any_of(s_.actions.begin(), s_.actions.end(), [](const sc::Action& a) { return a.verb == sc::Verb::raw; });
    if (raw) return;
    // The frame in flight at the end may have been taken without its answer arriving yet.
    const std::uint64_t open = b.client->in_flight_seq() ? 1U : 0U;
    if (c.given_up == 0 && open == 0) {
      if (taken != b.answered_frames || digest != b.answered_digest) {
        fail(who + ": the board took " + std::to_string(taken) + " frames, the client saw " +
             std::to_string(b.answered_frames) + " answered" + (digest != b.answered_digest ? " (not the same frames)" : ""));
      }
    } else if (taken < b.answered_frames || taken > b.answered_frames + c.given_up + open) {
      fail(who + ": the board took " + std::to_string(taken) + " frames; the client saw " + std::to_string(b.answered_frames) +
           " answered, gave up " + std::to_string(c.given_up) + " and has " + std::to_string(open) + " in flight");
    }
  }

  // The board-side echo model (every echo the core sent, docs/sim.md) and the PC-side
  // accounting of the echoes: the bus carried the board's TX stream exactly, and the link
  // lost no more of it than it says.
  void finish_echo_checks(BoardPc& b, std::int64_t t) {
    const std::string who = "board " + std::to_string(b.id);
    std::istringstream em(env(b, "probe echo_model", t));
    std::uint64_t checked = 0, disagreements = 0;
    if (!(em >> checked >> disagreements)) {
      fail("echo model: " + who + ": no answer to probe echo_model");
    } else {
      b.verdict.echoes_model_checked = checked;
      b.verdict.echo_disagreements = disagreements;
      for (std::uint64_t k = 0; k < std::min<std::uint64_t>(disagreements, 3); ++k) {
        std::string text;
        for (std::size_t off = 0; off < 2000; off += 100) {
          const std::string part = env(b, "probe echo_model." + std::to_string(k) + "." + std::to_string(off), t);
          if (part.empty()) break;
          text += part;
        }
        fail("echo model (board-side, every echo): " + who + ": " + text);
      }
      if (disagreements > 3) fail("echo model: " + who + ": " + std::to_string(disagreements - 3) + " more disagreements");
    }
    std::istringstream es(env(b, "probe echo_sent." + std::to_string(b.from_board.size()), t));
    std::uint64_t total = 0, digest = 0, queued = 0;
    if (!(es >> total >> digest >> queued)) {
      fail("echo check: " + who + ": the board sent fewer echoes than the bus brought (" +
           std::to_string(b.from_board.size()) + ")");
    } else {
      if (digest != b.from_board_digest) fail("echo check: " + who + ": the echoes the bus brought are not the board's TX stream");
      if (total != b.from_board.size() + queued) {
        fail("echo check: " + who + ": the board sent " + std::to_string(total) + " echoes, the bus brought " +
             std::to_string(b.from_board.size()) + " and " + std::to_string(queued) + " wait in its TX queue");
      }
    }
    const auto missing = static_cast<std::uint64_t>(std::count(b.delivered.begin(), b.delivered.end(), false));
    const LinkStats& up = b.verdict.to_pc;
    const std::uint64_t accounted = up.dropped + up.cut + b.up->in_flight();
    b.verdict.echoes_from_board = b.from_board.size();
    if (missing > accounted) {
      fail("echo check: " + who + ": " + std::to_string(missing) + " echoes the board sent never reached the PC; the link " +
           "dropped, cut or still holds " + std::to_string(accounted));
    }
  }

  const sc::Scenario& s_;
  const RunOptions& opt_;
  dds::ParticipantPtr pp_;
  std::vector<std::unique_ptr<BoardPc>> boards_;
  Mech mech_;
  std::vector<xy_codec::SubscriberId> subscribed_;
  std::vector<std::uint8_t> param_slots_;
  std::uint64_t round_trips_ = 0;
  std::vector<std::string> failures_;
  std::map<std::size_t, std::string> last_;
};

}  // namespace

RunResult run_pc(const sc::Scenario& s, const RunOptions& opt, std::uint32_t domain) {
  Pc pc(s, opt, domain);
  return pc.run();
}

}  // namespace ap::sim::xy
