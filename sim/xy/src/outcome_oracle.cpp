#include "sim/xy/outcome_oracle.hpp"

#include <sstream>

#include "protocol/xy/codec/commands.hpp"

namespace ap::sim::xy {

namespace {

std::string command_text(const xy_frame::AxisCommand& c) {
  const auto id = static_cast<std::uint32_t>(c.id);
  const std::string key = id < xy_codec::kCommands.size() ? std::string(xy_codec::kCommands[id].key) : std::to_string(id);
  return key + ":" + std::to_string(c.data);
}

const char* fate_words(const model::xy_echo::FrameFate& f, std::size_t part) {
  if (f.blocked) return "was answered BLOCKED_* without running";
  if (f.refused[part]) return "was refused";
  return "ran";
}

}  // namespace

std::string fate_text(const model::xy_echo::FrameFate& f) {
  auto refused = [](const std::optional<xy_codec::CommandId>& r) { return r ? static_cast<int>(*r) : -1; };
  std::ostringstream o;
  o << (f.blocked ? 1 : 0) << ' ' << static_cast<int>(f.frame.x.id) << ' ' << f.frame.x.data << ' '
    << static_cast<int>(f.frame.y.id) << ' ' << f.frame.y.data << ' ' << refused(f.refused[0]) << ' '
    << refused(f.refused[1]);
  return o.str();
}

std::optional<model::xy_echo::FrameFate> parse_fate(std::string_view text) {
  std::istringstream in{std::string(text)};
  int blocked = 0, xid = 0, yid = 0, rx = 0, ry = 0;
  std::int32_t xd = 0, yd = 0;
  if (!(in >> blocked >> xid >> xd >> yid >> yd >> rx >> ry)) return std::nullopt;
  model::xy_echo::FrameFate f;
  f.blocked = blocked != 0;
  f.frame.x = {static_cast<xy_codec::CommandId>(xid), xd};
  f.frame.y = {static_cast<xy_codec::CommandId>(yid), yd};
  if (rx >= 0) f.refused[0] = static_cast<xy_codec::CommandId>(rx);
  if (ry >= 0) f.refused[1] = static_cast<xy_codec::CommandId>(ry);
  return f;
}

xy_client::Outcome outcome_of(const model::xy_echo::FrameFate& f, std::size_t part) {
  if (f.blocked) return xy_client::Outcome::Blocked;
  if (f.refused[part]) return xy_client::Outcome::Refused;
  return xy_client::Outcome::Done;
}

std::optional<std::string> check_outcome(const xy_client::Report& r, const std::optional<model::xy_echo::FrameFate>& fate) {
  using xy_client::Outcome;
  const std::string what = std::string(command_text(r.command.cmd)) + " reported " + xy_client::to_string(r.outcome);
  switch (r.outcome) {
    case Outcome::Superseded:
    case Outcome::LinkDown:
    case Outcome::Invalid:
      if (r.seq) return what + " but it went out in frame " + std::to_string(*r.seq);
      return std::nullopt;
    case Outcome::Unconfirmed:
      return std::nullopt;
    case Outcome::Done:
    case Outcome::Refused:
    case Outcome::Blocked:
      break;
  }
  if (!r.seq || !r.part || *r.part > 1) return what + " without the frame and part that carried it";
  const std::string frame = "frame " + std::to_string(*r.seq);
  if (!fate) return what + " but the board never took " + frame;
  const xy_frame::AxisCommand& carried = *r.part == 0 ? fate->frame.x : fate->frame.y;
  if (!(carried == r.command.cmd)) {
    return what + " but " + frame + " carried " + command_text(carried) + " in its " + (*r.part == 0 ? "X" : "Y") + " part";
  }
  const Outcome want = outcome_of(*fate, *r.part);
  if (want == r.outcome) return std::nullopt;
  return what + " but in " + frame + " it " + fate_words(*fate, *r.part) + " (" + xy_client::to_string(want) + ")";
}

}  // namespace ap::sim::xy
