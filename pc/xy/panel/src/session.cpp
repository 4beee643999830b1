// The panel's PC side (session.hpp, docs/panel.md): the requests of the page turned into the
// delivery client's commands, one bus step per board and period in real time, and what the
// echoes, the subscribers and the settled commands say, published for the page.
#include "pc/xy/panel/session.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/xy/storage/fram_map.hpp"
#include "pc/dds/bus.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "pc/xy/client/client.hpp"
#include "pc/xy/client/readable.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::xy_panel {

using json = nlohmann::json;
using xy_codec::CommandId;
using xy_codec::SubscriberId;

namespace {

// Parameters the Dynamics panel shows, read back through the param subscriber in turn.
constexpr std::array kShownParams{xy_storage::ParamId::FastSpeed, xy_storage::ParamId::SlowSpeed,
                                  xy_storage::ParamId::MaxAcceleration};

const char* param_key(xy_storage::ParamId p) {
  switch (p) {
    case xy_storage::ParamId::FastSpeed: return "fast";
    case xy_storage::ParamId::SlowSpeed: return "slow";
    default: return "accel";
  }
}

std::string status_key(xy_codec::EchoStatus s) { return std::string(xy_codec::kStatuses[static_cast<std::size_t>(s)].key); }

// Commands the operator may not send from the panel: the factory parameters (docs/storage.md
// "Factory and user parameters") and the path frames, which only the G-code program sends as
// whole segments (docs/cnc.md "On the board").
bool operator_command(CommandId id) {
  switch (id) {
    case CommandId::SetPitch:
    case CommandId::SetSteps:
    case CommandId::SetMicrosteps:
    case CommandId::SetIrun:
    case CommandId::SetIhold:
    case CommandId::PathLine:
    case CommandId::PathCentre:
    case CommandId::PathArcCw:
    case CommandId::PathArcCcw:
    case CommandId::PathEnd:
      return false;
    default:
      return true;
  }
}

// Motion commands go in their axis's part; settings and unit commands in either (the simulated
// PC sends the speeds and the acceleration as unit commands, docs/sim.md).
bool axis_only(CommandId id) {
  switch (id) {
    case CommandId::Stop:
    case CommandId::Jog:
    case CommandId::Goto:
    case CommandId::Move:
    case CommandId::Home:
    case CommandId::GotoSlow:
    case CommandId::MoveSlow:
      return true;
    default:
      return false;
  }
}

}  // namespace

struct Session::Pending {
  enum class Kind { Command, Hold, Connect, Env, SimEcho } kind = Kind::Command;
  std::uint32_t board = 0;
  xy_client::Command command{};
  int axis = 0;
  int level = 0;
  bool on = false;
  std::string line;
  xy_frame::AxisEcho echo{};  // SimEcho
  std::promise<Accepted> accepted;
  std::promise<std::string> reply;
};

struct Session::Board {
  std::uint32_t id = 0;
  std::unique_ptr<dds::PcEndpoint> ep;
  std::unique_ptr<xy_client::Client> client;
  std::unique_ptr<LinkFilter> link;
  bool on_bus = false;
  bool connected = false;
  bool in_range = false;
  std::array<std::int32_t, 2> jog{};
  std::array<xy_frame::AxisEcho, 2> axis{};
  std::array<xy_frame::AxisEcho, 2> simulated{};
  std::int64_t simulated_until_us = -1;
  std::optional<std::int64_t> last_answer_us;
  std::int64_t prev_answer_us = 0;
  json subs = json::object();
  json params = json::object();
  std::string last_frame;  // the last frame the client put on the wire, readable (xy_client::to_readable)
  dds::Telemetry truth{};
  std::uint32_t param_turn = 0;
};

Session::Session(Options o) : opt_(std::move(o)) {
  for (const std::uint32_t id : opt_.boards) {
    auto b = std::make_unique<Board>();
    b->id = id;
    b->ep = std::make_unique<dds::PcEndpoint>(opt_.domain, id);
    if (opt_.link) b->link = opt_.link(id);
    boards_.push_back(std::move(b));
  }
  event({{"type", "connection"}, {"board", -1}, {"what", "search started (BleDeviceStartScanningEvent)"}});
  loop_ = std::make_unique<web::PacedLoop>(
      opt_.period_us, [this](std::int64_t t) { step(t); },
      [this](const std::string& what) { event({{"type", "error"}, {"board", -1}, {"what", what}}); });
}

Session::~Session() { stop(); }

void Session::stop() {
  if (loop_) loop_->stop();
  // Anything still waiting, or coming later, gets an answer, so no HTTP thread hangs.
  std::lock_guard<std::mutex> l(mu_);
  stopped_ = true;
  for (auto& p : pending_) answer_shut_down(*p);
  pending_.clear();
}

json Session::tables() {
  json t;
  t["commands"] = json::array();
  for (const auto& c : xy_codec::kCommands) {
    if (!operator_command(c.id)) continue;
    t["commands"].push_back({{"key", c.key}, {"meaning", c.meaning}, {"unit", c.unit}, {"min", c.range.min},
                             {"max", c.range.max}, {"axis", axis_only(c.id)}});
  }
  t["statuses"] = json::array();
  for (const auto& s : xy_codec::kStatuses) t["statuses"].push_back({{"key", s.key}, {"meaning", s.meaning}, {"data", s.data}});
  return t;
}

Accepted Session::submit(const Request& r) {
  const xy_codec::CommandInfo* c = xy_codec::find_command(r.key);
  if (c == nullptr) return {false, "unknown command '" + r.key + "'", 0};
  if (!operator_command(c->id)) return {false, "'" + r.key + "' is not an operator command (factory setting or path frame)", 0};
  xy_client::Part part;
  if (r.part == "x") {
    part = xy_client::Part::X;
  } else if (r.part == "y") {
    part = xy_client::Part::Y;
  } else if (r.part == "unit") {
    part = xy_client::Part::Unit;
  } else {
    return {false, "part must be x, y or unit", 0};
  }
  if (axis_only(c->id) && part == xy_client::Part::Unit) return {false, "'" + r.key + "' needs an axis (x or y)", 0};
  if (r.data < c->range.min || r.data > c->range.max) {
    return {false, std::string(c->meaning) + ": " + std::to_string(r.data) + " outside " + std::to_string(c->range.min) + ".." +
                       std::to_string(c->range.max) + " " + std::string(c->unit),
            0};
  }
  auto p = std::make_unique<Pending>();
  p->kind = Pending::Kind::Command;
  p->board = r.board;
  p->command = {part, {c->id, static_cast<std::int32_t>(r.data)}};
  return queue(std::move(p));
}

Accepted Session::hold(std::uint32_t board, int axis, int level) {
  if (axis < 0 || axis > 1) return {false, "axis must be 0 (X) or 1 (Y)", 0};
  if (level < -xy_codec::kJogFast || level > xy_codec::kJogFast) return {false, "jog level outside -2..2", 0};
  auto p = std::make_unique<Pending>();
  p->kind = Pending::Kind::Hold;
  p->board = board;
  p->axis = axis;
  p->level = level;
  return queue(std::move(p));
}

Accepted Session::connect(std::uint32_t board, bool on) {
  auto p = std::make_unique<Pending>();
  p->kind = Pending::Kind::Connect;
  p->board = board;
  p->on = on;
  return queue(std::move(p));
}

Accepted Session::simulate_echo(std::uint32_t board, const std::string& status, std::int32_t data) {
  const xy_codec::StatusInfo* st = xy_codec::find_status(status);
  if (st == nullptr) return {false, "unknown status '" + status + "'", 0};
  if (data < st->range.min || data > st->range.max) {
    return {false, std::string(st->data) + " " + std::to_string(data) + " outside " + std::to_string(st->range.min) + ".." +
                       std::to_string(st->range.max),
            0};
  }
  auto p = std::make_unique<Pending>();
  p->kind = Pending::Kind::SimEcho;
  p->board = board;
  p->echo = {st->id, data};
  return queue(std::move(p));
}

std::string Session::env(std::uint32_t board, const std::string& line) {
  auto p = std::make_unique<Pending>();
  p->kind = Pending::Kind::Env;
  p->board = board;
  p->line = line;
  auto f = p->reply.get_future();
  push(std::move(p));
  return f.get();
}

Accepted Session::queue(std::unique_ptr<Pending> p) {
  auto f = p->accepted.get_future();
  push(std::move(p));
  return f.get();
}

void Session::push(std::unique_ptr<Pending> p) {
  std::lock_guard<std::mutex> l(mu_);
  if (stopped_) {
    answer_shut_down(*p);
    return;
  }
  pending_.push_back(std::move(p));
}

void Session::answer_shut_down(Pending& p) {
  if (p.kind == Pending::Kind::Env) {
    p.reply.set_value("err the panel is shutting down");
  } else {
    p.accepted.set_value({false, "the panel is shutting down", 0});
  }
}

json Session::snapshot(std::uint64_t after) const { return pub_.snapshot(after); }

void Session::step(std::int64_t t) {
  std::deque<std::unique_ptr<Pending>> work;
  {
    std::lock_guard<std::mutex> l(mu_);
    work.swap(pending_);
  }
  const auto find = [&](std::uint32_t id) -> Board* {
    for (auto& b : boards_) {
      if (b->id == id) return b.get();
    }
    return nullptr;
  };
  for (auto& p : work) {
    Board* b = find(p->board);
    if (p->kind == Pending::Kind::Env) {
      if (b == nullptr || !b->on_bus) {
        p->reply.set_value("err board " + std::to_string(p->board) + " is not on the bus");
        continue;
      }
      const std::vector<std::uint8_t> bytes(p->line.begin(), p->line.end());
      const std::uint64_t seq = b->ep->send(bytes, static_cast<std::uint64_t>(t), dds::kFlagEnv);
      std::string reply = "err no answer";
      for (int k = 0; k < 100; ++k) {
        auto e = b->ep->take_echo(std::chrono::milliseconds(100));
        if (e && e->cmd_seq == seq) {
          reply.assign(e->bytes.begin(), e->bytes.end());
          break;
        }
      }
      event({{"type", "env"}, {"board", b->id}, {"line", p->line}, {"reply", reply}});
      p->reply.set_value(reply);
      continue;
    }
    if (b == nullptr) {
      p->accepted.set_value({false, "no board " + std::to_string(p->board), 0});
      continue;
    }
    if (p->kind == Pending::Kind::Connect) {
      if (p->on && !b->on_bus) {
        p->accepted.set_value({false, "board " + std::to_string(b->id) + " is not on the bus", 0});
        continue;
      }
      if (p->on && !b->connected) {
        xy_client::Config cc;
        cc.keepalive_us = 100'000;  // thesis §6.2: a frame every 100 ms when idle
        // Sequence numbers carry on from the last session, so the board takes the new frames
        // as newer (docs/protocol.md "Delivery").
        if (b->client) cc.first_seq = b->client->next_seq();
        b->client = std::make_unique<xy_client::Client>(cc);
        b->connected = true;
        b->jog = {0, 0};
        event({{"type", "connection"}, {"board", b->id}, {"what", "connected (BleDeviceConnectedEvent)"}});
      } else if (!p->on && b->connected) {
        event({{"type", "connection"}, {"board", b->id}, {"what", "disconnecting (BleDeviceDisconnectingEvent)"}});
        b->connected = false;
        b->in_range = false;
        event({{"type", "connection"}, {"board", b->id}, {"what", "disconnected (BleDeviceDisconnectedEvent)"}});
      }
      p->accepted.set_value({true, "", 0});
      continue;
    }
    if (!b->connected || !b->client) {
      p->accepted.set_value({false, "board " + std::to_string(b->id) + " is not connected", 0});
      continue;
    }
    if (p->kind == Pending::Kind::SimEcho) {
      const xy_frame::AxisEcho e = p->echo;
      b->simulated = {e, e};
      b->simulated_until_us = t + 3'000'000;
      event({{"type", "connection"}, {"board", b->id}, {"what", "simulated echo: " + status_key(e.status) + " on both axes"}});
      p->accepted.set_value({true, "", 0});
      continue;
    }
    if (p->kind == Pending::Kind::Hold) {
      const auto part = p->axis == 0 ? xy_client::Part::X : xy_client::Part::Y;
      // A key press is a jog command like any other; its level then rides in every new frame
      // (pc/xy/client Extras), and the release is a jog of level 0 (a ramped stop).
      b->jog[static_cast<std::size_t>(p->axis)] = p->level;
      const auto tk = b->client->submit({part, {CommandId::Jog, p->level}}, t);
      p->accepted.set_value({true, "", tk});
      continue;
    }
    const std::size_t ai = p->command.part == xy_client::Part::Y ? 1 : 0;
    if (p->command.part != xy_client::Part::Unit && axis_only(p->command.cmd.id)) b->jog[ai] = 0;
    const auto tk = b->client->submit(p->command, t);
    p->accepted.set_value({true, "", tk});
  }

  json boards = json::array();
  for (auto& bp : boards_) {
    Board& b = *bp;
    if (!b.on_bus) {
      if (!b.ep->wait_matched(std::chrono::milliseconds(0))) {
        boards.push_back({{"id", b.id}, {"on_bus", false}});
        continue;
      }
      b.on_bus = true;
      event({{"type", "connection"}, {"board", b.id}, {"what", "found, in range of the PC (BleDeviceIdFoundEvent)"}});
    }
    std::string bytes;
    if (b.connected) {
      xy_client::Extras ex;
      ex.jog = b.jog;
      ex.subs[0] = {SubscriberId::BatteryMv, 0};
      ex.subs[1] = {SubscriberId::ChargeMa, 0};
      ex.subs[2] = {SubscriberId::TemperatureMc, 0};
      const std::uint32_t turn = b.param_turn++ % (kShownParams.size() + 1);
      ex.subs[3] = turn == kShownParams.size() ? xy_frame::SubscriberSlot{SubscriberId::RotationMdeg, 0}
                                               : xy_frame::SubscriberSlot{SubscriberId::Param, static_cast<std::uint8_t>(kShownParams[turn])};
      if (auto text = b.client->poll(t, ex)) {
        bytes = *text;
        xy_frame::CommandFrame f;
        const std::span<const std::uint8_t> raw(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        if (xy_frame::parse_command(raw, f).ok()) b.last_frame = xy_client::to_readable(f);
      }
    }
    if (b.link) bytes = b.link->to_board(t, bytes);
    const std::vector<std::uint8_t> out(bytes.begin(), bytes.end());
    std::optional<dds::EchoSample> echo;
    try {
      echo = b.ep->step(out, static_cast<std::uint64_t>(t), std::chrono::seconds(2));
    } catch (const dds::Error&) {
      // No answer in 2 s: the board has left the bus.
    }
    if (!echo) {
      if (b.on_bus) event({{"type", "connection"}, {"board", b.id}, {"what", "gone from the bus: disconnected (BleDeviceDisconnectedEvent)"}});
      b.on_bus = false;
      b.connected = false;
      b.in_range = false;
      boards.push_back({{"id", b.id}, {"on_bus", false}});
      continue;
    }
    b.truth = echo->telemetry;
    std::string back(echo->bytes.begin(), echo->bytes.end());
    if (b.link) back = b.link->to_pc(t, back);
    if (b.connected) {
      for (const auto& ev : b.client->receive(back, t)) {
        if (ev.kind == xy_client::EchoKind::Rejected || ev.kind == xy_client::EchoKind::Malformed) continue;
        b.axis = {ev.echo.x, ev.echo.y};
        if (b.last_answer_us) b.prev_answer_us = *b.last_answer_us;
        b.last_answer_us = t;
        for (const auto& s : ev.echo.subs) {
          switch (s.slot.id) {
            case SubscriberId::BatteryMv: b.subs["battery_mv"] = s.data; break;
            case SubscriberId::ChargeMa: b.subs["charge_ma"] = s.data; break;
            case SubscriberId::TemperatureMc: b.subs["temperature_mc"] = s.data; break;
            case SubscriberId::RotationMdeg: b.subs["rotation_mdeg"] = s.data; break;
            case SubscriberId::Param: b.params[param_key(static_cast<xy_storage::ParamId>(s.slot.arg))] = s.data; break;
            default: break;
          }
        }
      }
      // The unit is in range while its echoes keep coming (thesis §8.2: the indicator changes
      // when the unit is out of range).
      const bool in_range = b.last_answer_us && t - *b.last_answer_us <= opt_.out_of_range_us;
      if (in_range != b.in_range) {
        event({{"type", "connection"}, {"board", b.id}, {"what", in_range ? "unit in range" : "unit out of range (no answer)"}});
        b.in_range = in_range;
      }
      for (const auto& r : b.client->take_reports()) {
        const auto& info = xy_codec::info(r.command.cmd.id);
        event({{"type", "outcome"},
               {"board", b.id},
               {"ticket", r.ticket},
               {"command", info.key},
               {"part", r.command.part == xy_client::Part::X ? "x" : (r.command.part == xy_client::Part::Y ? "y" : "unit")},
               {"data", r.command.cmd.data},
               {"outcome", xy_client::to_string(r.outcome)},
               {"status", status_key(r.status)},
               {"transmissions", r.transmissions}});
      }
    }
    json axes = json::array();
    const bool simulated = t < b.simulated_until_us;
    for (std::size_t a = 0; a < 2; ++a) {
      const auto& ae = simulated ? b.simulated[a] : b.axis[a];
      const auto& info = xy_codec::kStatuses[static_cast<std::size_t>(ae.status)];
      axes.push_back({{"status", info.key}, {"wording", info.meaning}, {"data", ae.data}, {"jog", b.jog[a]},
                      {"simulated", simulated}, {"board_usteps", b.truth.axis[a].pos}});
    }
    const auto& cn = b.client ? b.client->counters() : xy_client::ClientCounters{};
    boards.push_back({{"id", b.id},
                      {"on_bus", true},
                      {"connected", b.connected},
                      {"in_range", b.in_range},
                      {"axes", axes},
                      {"subs", b.subs},
                      {"params", b.params},
                      {"last_frame", b.last_frame},
                      {"link", {{"sent", cn.sent}, {"retransmissions", cn.retransmissions}, {"delivered", cn.delivered},
                                {"failed", cn.failed}, {"link_down", b.client ? b.client->link_down() : false}}}});
  }
  pub_.state({{"t_us", t}, {"boards", std::move(boards)}});
}

}  // namespace ap::xy_panel
