#include "pc/xy/client/readable.hpp"

#include <charconv>
#include <sstream>
#include <vector>

#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/errors.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_builder.hpp"

namespace ap::xy_client {

namespace c = ap::xy_codec;

namespace {

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const auto pos = s.find(sep, start);
    parts.push_back(s.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start));
    if (pos == std::string_view::npos) return parts;
    start = pos + 1;
  }
}

bool to_int(std::string_view s, std::int32_t& v) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, v);
  return !s.empty() && r.ec == std::errc{} && r.ptr == end;
}

std::string parse_axis(std::string_view value, xy_frame::AxisCommand& out) {
  const auto parts = split(value, ':');
  const auto* info = c::find_command(parts[0]);
  if (info == nullptr) return "unknown command '" + std::string(parts[0]) + "'";
  std::int32_t data = 0;
  if (info->id == c::CommandId::Jog && parts.size() == 3) {
    if (parts[1] != "+" && parts[1] != "-") return "jog direction must be + or -";
    if (parts[2] != "fast" && parts[2] != "slow") return "jog speed must be fast or slow";
    data = parts[2] == "fast" ? c::kJogFast : c::kJogSlow;
    if (parts[1] == "-") data = -data;
  } else if (parts.size() == 2) {
    if (!to_int(parts[1], data)) return "bad number '" + std::string(parts[1]) + "'";
  } else if (parts.size() != 1) {
    return "too many ':' in '" + std::string(value) + "'";
  }
  if (!info->range.contains(data)) {
    return std::string(info->key) + " data " + std::to_string(data) + " outside [" + std::to_string(info->range.min) +
           ", " + std::to_string(info->range.max) + "]";
  }
  out = {info->id, data};
  return {};
}

std::string parse_sub(std::string_view value, xy_frame::SubscriberSlot& out) {
  const auto parts = split(value, ':');
  const auto* info = c::find_subscriber(parts[0]);
  if (info == nullptr) return "unknown subscriber '" + std::string(parts[0]) + "'";
  std::int32_t arg = 0;
  if (parts.size() == 2) {
    if (!to_int(parts[1], arg)) return "bad argument '" + std::string(parts[1]) + "'";
  } else if (parts.size() != 1) {
    return "too many ':' in '" + std::string(value) + "'";
  }
  if (!info->arg_range.contains(arg)) return std::string(info->key) + " argument " + std::to_string(arg) + " out of range";
  out = {info->id, static_cast<std::uint8_t>(arg)};
  return {};
}

}  // namespace

std::string parse_readable(std::string_view text, xy_frame::CommandFrame& out) {
  xy_frame::CommandFrame f;
  std::size_t subs = 0;
  std::istringstream in{std::string(text)};
  std::string token;
  while (in >> token) {
    const auto eq = token.find('=');
    if (eq == std::string::npos) return "expected key=value, got '" + token + "'";
    const std::string_view key(token.data(), eq);
    const std::string_view value = std::string_view(token).substr(eq + 1);
    std::string err;
    if (key == "x") {
      err = parse_axis(value, f.x);
    } else if (key == "y") {
      err = parse_axis(value, f.y);
    } else if (key == "sub") {
      if (subs == f.subs.size()) return "at most " + std::to_string(f.subs.size()) + " subscribers";
      err = parse_sub(value, f.subs[subs++]);
    } else if (key == "seq") {
      std::int32_t seq = 0;
      if (!to_int(value, seq) || seq < 0 || seq >= c::kSeqModulo) return "seq must be 0..999";
      f.seq = static_cast<std::uint16_t>(seq);
    } else {
      return "unknown key '" + std::string(key) + "' (x, y, sub, seq)";
    }
    if (!err.empty()) return err;
  }
  out = f;
  return {};
}

std::string to_readable(const xy_frame::CommandFrame& f) {
  std::ostringstream o;
  o << "seq=" << f.seq;
  o << " x=" << c::info(f.x.id).key << ':' << f.x.data;
  o << " y=" << c::info(f.y.id).key << ':' << f.y.data;
  for (const auto& s : f.subs) {
    if (s.id == c::SubscriberId::None) continue;
    o << " sub=" << c::kSubscribers[static_cast<std::size_t>(s.id)].key << ':' << int{s.arg};
  }
  return o.str();
}

std::string describe(const xy_frame::Rejection& r) {
  std::ostringstream o;
  const auto i = static_cast<std::size_t>(r.error);
  o << c::error_key(r.error) << " at byte " << r.offset;
  if (i < c::kFrameErrors.size()) o << " (" << c::kFrameErrors[i].meaning << ")";
  return o.str();
}

std::string describe(const xy_frame::CommandFrame& f) {
  std::ostringstream o;
  o << "command seq=" << f.seq << "\n";
  const auto axis = [&o](const char* name, const xy_frame::AxisCommand& a) {
    const auto& info = c::info(a.id);
    o << "  " << name << ": " << info.key << " (id " << static_cast<int>(a.id) << ") data=" << a.data << ' ' << info.unit
      << "  [" << info.meaning << "]\n";
  };
  axis("x", f.x);
  axis("y", f.y);
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    const auto& info = c::kSubscribers[static_cast<std::size_t>(f.subs[i].id)];
    o << "  sub" << i << ": " << info.key << " (id " << static_cast<int>(f.subs[i].id) << ") arg=" << int{f.subs[i].arg}
      << "\n";
  }
  o << "  readable: " << to_readable(f) << "\n";
  return o.str();
}

std::string describe(const xy_frame::EchoFrame& f) {
  std::ostringstream o;
  o << "echo seq=" << f.seq << "\n";
  const auto axis = [&o](const char* name, const xy_frame::AxisEcho& a) {
    const auto& info = c::kStatuses[static_cast<std::size_t>(a.status)];
    o << "  " << name << ": " << info.key << " (id " << static_cast<int>(a.status) << ") " << info.data << '='
      << a.data << ' ' << info.unit;
    if (a.status == c::EchoStatus::FrameRejected) o << "  [" << describe(xy_frame::rejection_from_code(a.data)) << "]";
    o << "\n";
  };
  axis("x", f.x);
  axis("y", f.y);
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    const auto& p = f.subs[i];
    const auto& info = c::kSubscribers[static_cast<std::size_t>(p.slot.id)];
    o << "  sub" << i << ": " << info.key << " (id " << static_cast<int>(p.slot.id) << ") arg=" << int{p.slot.arg}
      << " data=" << p.data << ' ' << info.unit << "\n";
  }
  return o.str();
}

}  // namespace ap::xy_client
