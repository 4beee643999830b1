#include "pc/xy/client/client.hpp"

#include <algorithm>
#include <array>

#include "protocol/xy/codec/commands.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_builder.hpp"
#include "core/xy/frame/echo_codec.hpp"

namespace ap::xy_client {

namespace c = ap::xy_codec;

std::string to_string(std::span<const std::uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

std::optional<std::string> format(const xy_frame::CommandFrame& f) {
  std::array<std::uint8_t, xy_codec::kCommandLength> out{};
  if (!xy_frame::format_command(f, out).ok()) return std::nullopt;
  return to_string(out);
}

std::optional<std::string> format(const xy_frame::EchoFrame& f) {
  std::array<std::uint8_t, xy_codec::kEchoLength> out{};
  if (!xy_frame::format_echo(f, out).ok()) return std::nullopt;
  return to_string(out);
}

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::Done: return "done";
    case Outcome::Refused: return "refused";
    case Outcome::Blocked: return "blocked";
    case Outcome::Superseded: return "superseded";
    case Outcome::Unconfirmed: return "unconfirmed";
    case Outcome::LinkDown: return "link_down";
    case Outcome::Invalid: return "invalid";
  }
  return "?";
}

namespace {

// docs/protocol.md rule 5: a stop of either axis stops the path, and the board drops its
// queue (docs/cnc.md "Stops").
bool path_command(c::CommandId id) {
  return id == c::CommandId::PathLine || id == c::CommandId::PathCentre || id == c::CommandId::PathArcCw ||
         id == c::CommandId::PathArcCcw || id == c::CommandId::PathEnd;
}

bool moves_axis(c::CommandId id) {
  return id == c::CommandId::Goto || id == c::CommandId::Move || id == c::CommandId::GotoSlow ||
         id == c::CommandId::MoveSlow || id == c::CommandId::Home || id == c::CommandId::Jog;
}

// docs/storage.md "Factory and user parameters": the commands that set a factory item.
bool sets_factory_parameter(c::CommandId id) {
  return id == c::CommandId::SetPitch || id == c::CommandId::SetSteps || id == c::CommandId::SetMicrosteps ||
         id == c::CommandId::SetIrun || id == c::CommandId::SetIhold;
}

bool is_stop(const Command& cmd) { return cmd.part != Part::Unit && cmd.cmd.id == c::CommandId::Stop; }

bool blocked_status(c::EchoStatus s) {
  return s == c::EchoStatus::BlockedUsb || s == c::EchoStatus::BlockedCharger || s == c::EchoStatus::BlockedBattery;
}

// Seqs ahead of `from` (mod 1000).
unsigned ahead(std::uint16_t from, std::uint16_t to) {
  return (static_cast<unsigned>(to) + c::kSeqModulo - from) % c::kSeqModulo;
}

}  // namespace

Client::Client(Config cfg) : cfg_(cfg), next_seq_(static_cast<std::uint16_t>(cfg.first_seq % c::kSeqModulo)) {}

std::optional<std::uint16_t> Client::in_flight_seq() const {
  if (!in_flight_) return std::nullopt;
  return in_flight_->frame.seq;
}

Ticket Client::submit(const Command& cmd, std::int64_t now_us) {
  const Pending p{next_ticket_++, cmd, now_us, {}};
  ++counters_.commands;
  // A command the tables do not admit is refused here, before it can take a seq.
  xy_frame::CommandFrame probe;
  (cmd.part == Part::Y ? probe.y : probe.x) = cmd.cmd;
  if (!format(probe) || (sets_factory_parameter(cmd.cmd.id) && !cfg_.factory)) {
    report(p, Outcome::Invalid, now_us, nullptr, nullptr);
    return p.ticket;
  }
  if (link_down_) {
    report(p, Outcome::LinkDown, now_us, nullptr, nullptr);
    return p.ticket;
  }
  if (!is_stop(cmd)) {
    queue_.push_back(p);
    return p.ticket;
  }
  // A stop goes ahead of everything queued (behind other stops), and the motion commands of
  // its axis issued before it are cancelled: sent after the stop they would move the axis the
  // user just stopped; so are the path's commands, which move both. The frame in flight is not
  // touched: it may already have run.
  for (auto it = queue_.begin(); it != queue_.end();) {
    if ((it->command.part == cmd.part && moves_axis(it->command.cmd.id)) || path_command(it->command.cmd.id)) {
      report(*it, Outcome::Superseded, now_us, nullptr, nullptr);
      it = queue_.erase(it);
    } else {
      ++it;
    }
  }
  auto pos = queue_.begin();
  while (pos != queue_.end() && is_stop(pos->command)) {
    if (pos->command.part == cmd.part) {
      pos->riders.emplace_back(p.ticket, now_us);
      return p.ticket;
    }
    ++pos;
  }
  queue_.insert(pos, p);
  return p.ticket;
}

std::int64_t Client::retransmit_interval() const {
  // A frame carrying commands, or one that commands wait behind, is repeated quickly; a
  // keep-alive with nothing behind it at the keep-alive period.
  const bool urgent = (in_flight_ && !in_flight_->commands.empty()) || !queue_.empty();
  return urgent ? cfg_.retransmit_us : cfg_.keepalive_us;
}

std::optional<std::string> Client::poll(std::int64_t now_us, const Extras& extras) {
  if (in_flight_) {
    InFlight& f = *in_flight_;
    const bool timed_out = now_us - f.last_sent_us >= retransmit_interval();
    if (!f.resend_now && !timed_out) return std::nullopt;
    if (timed_out) ++counters_.timeouts;
    if (f.transmissions < cfg_.max_transmissions) {
      ++counters_.retransmissions;
      return send(now_us);
    }
    // Out of transmissions: the link is down. The frame's commands may or may not have run
    // (at most once: the board never runs a seq twice); what waits behind it never went out.
    ++counters_.given_up;
    const InFlight gone = std::move(f);
    in_flight_.reset();
    for (const Pending& p : gone.commands) report(p, Outcome::Unconfirmed, now_us, &gone, nullptr);
    for (const Pending& p : queue_) report(p, Outcome::LinkDown, now_us, nullptr, nullptr);
    queue_.clear();
    link_down_ = true;
  }
  if (queue_.empty() && last_new_frame_us_ && now_us - *last_new_frame_us_ < cfg_.keepalive_us) return std::nullopt;
  start_frame(now_us, extras);
  return send(now_us);
}

void Client::start_frame(std::int64_t now_us, const Extras& extras) {
  InFlight f;
  f.frame.seq = next_seq_;
  next_seq_ = c::seq_next(next_seq_);
  f.frame.subs = extras.subs;
  std::array<bool, 2> used{};
  auto place = [&](int part) {
    const Pending p = queue_.front();
    queue_.pop_front();
    (part == 0 ? f.frame.x : f.frame.y) = p.command.cmd;
    used[static_cast<std::size_t>(part)] = true;
    f.part_of[f.commands.size()] = part;
    f.commands.push_back(p);
  };
  if (!queue_.empty()) {
    const Part first = queue_.front().command.part;
    // A unit command takes a part whose axis holds no jog, so the jog's keep-alive rides along.
    const int part = first == Part::X ? 0 : first == Part::Y ? 1 : (extras.jog[0] == 0 || extras.jog[1] != 0 ? 0 : 1);
    place(part);
    // The X part runs before the Y part, so a second command fits only behind one in X; two
    // stops of different axes commute, so a stop of X also rides behind a stop of Y.
    if (part == 0 && !queue_.empty() && queue_.front().command.part != Part::X) {
      place(1);
    } else if (part == 1 && is_stop(f.commands.front().command) && !queue_.empty() && is_stop(queue_.front().command) &&
               queue_.front().command.part == Part::X) {
      place(0);
    }
  }
  for (std::size_t i = 0; i < 2; ++i) {
    if (used[i]) continue;
    (i == 0 ? f.frame.x : f.frame.y) =
        extras.jog[i] != 0 ? xy_frame::AxisCommand{c::CommandId::Jog, extras.jog[i]} : xy_frame::AxisCommand{};
  }
  auto bytes = format(f.frame);
  if (!bytes) {
    // Only the jog levels or the slots can be out of range here (commands were checked when
    // submitted): send the frame without them.
    for (std::size_t i = 0; i < 2; ++i) {
      if (!used[i]) (i == 0 ? f.frame.x : f.frame.y) = xy_frame::AxisCommand{};
    }
    f.frame.subs = {};
    bytes = format(f.frame);
  }
  f.bytes = bytes.value_or(std::string());
  ++counters_.new_frames;
  last_new_frame_us_ = now_us;
  in_flight_ = std::move(f);
}

std::string Client::send(std::int64_t now_us) {
  InFlight& f = *in_flight_;
  if (f.transmissions == 0) f.first_sent_us = now_us;
  ++f.transmissions;
  f.last_sent_us = now_us;
  f.resend_now = false;
  ++counters_.sent;
  return f.bytes;
}

void Client::report(const Pending& p, Outcome o, std::int64_t now_us, const InFlight* f, const xy_frame::AxisEcho* part) {
  Report r;
  r.ticket = p.ticket;
  r.command = p.command;
  r.outcome = o;
  r.issued_us = p.issued_us;
  r.settled_us = now_us;
  if (f != nullptr) {
    r.seq = f->frame.seq;
    r.first_sent_us = f->first_sent_us;
    r.transmissions = f->transmissions;
    for (std::size_t j = 0; j < f->commands.size(); ++j) {
      if (f->commands[j].ticket == p.ticket) r.part = static_cast<std::uint8_t>(f->part_of[j]);
    }
  }
  if (part != nullptr) {
    r.status = part->status;
    r.data = part->data;
  }
  const bool ok = delivered(r.outcome);
  (ok ? counters_.delivered : counters_.failed) += 1;
  reports_.push_back(r);
  for (const auto& [ticket, issued] : p.riders) {
    r.ticket = ticket;
    r.issued_us = issued;
    (ok ? counters_.delivered : counters_.failed) += 1;
    reports_.push_back(r);
  }
}

void Client::settle(const xy_frame::EchoFrame& echo, std::int64_t now_us) {
  const InFlight f = std::move(*in_flight_);
  in_flight_.reset();
  link_down_ = false;
  ++counters_.answered;
  for (std::size_t j = 0; j < f.commands.size(); ++j) {
    const xy_frame::AxisEcho& part = f.part_of[j] == 0 ? echo.x : echo.y;
    const Outcome o = part.status == c::EchoStatus::CommandRefused ? Outcome::Refused
                      : blocked_status(part.status)                 ? Outcome::Blocked
                                                                    : Outcome::Done;
    report(f.commands[j], o, now_us, &f, &part);
  }
}

std::vector<EchoEvent> Client::receive(const std::string& bytes, std::int64_t now_us) {
  return receive(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), now_us);
}

std::vector<EchoEvent> Client::receive(std::span<const std::uint8_t> bytes, std::int64_t now_us) {
  std::vector<EchoEvent> events;
  framer_.feed(bytes, [&](const xy_frame::EchoFramer::Event& e) { events.push_back(classify(e, now_us)); });
  return events;
}

EchoEvent Client::classify(const xy_frame::EchoFramer::Event& e, std::int64_t now_us) {
  EchoEvent ev;
  ev.stream_offset = e.stream_offset;
  if (!e.rejection.ok()) {
    ev.kind = EchoKind::Malformed;
    ev.rejection = e.rejection;
    ++counters_.malformed;
    return ev;
  }
  ev.echo = e.frame;
  if (e.frame.x.status == c::EchoStatus::FrameRejected || e.frame.y.status == c::EchoStatus::FrameRejected) {
    // The board saw a damaged frame (most likely ours): it ran nothing, so the frame in flight
    // goes out again now rather than after the timeout. Never an answer.
    const auto& part = e.frame.x.status == c::EchoStatus::FrameRejected ? e.frame.x : e.frame.y;
    ev.kind = EchoKind::Rejected;
    ev.rejection = xy_frame::rejection_from_code(part.data);
    ++counters_.rejected;
    if (in_flight_) in_flight_->resend_now = true;
    return ev;
  }
  if (in_flight_ && e.frame.seq == in_flight_->frame.seq) {
    ev.kind = EchoKind::Answer;
    ev.answered = in_flight_->frame;
    settle(e.frame, now_us);
    return ev;
  }
  // An echo carries the seq of the last frame the board took. Ahead of the frame in flight
  // (1..500: half the seq space, the board's "older" side included) means the board took frames
  // this client never sent (another sender, or a client restarted at seq 0): renumber the frame
  // in flight behind the board's, or the board would answer it as older forever.
  if (in_flight_) {
    const unsigned d = ahead(in_flight_->frame.seq, e.frame.seq);
    if (d >= 1 && d <= c::kSeqModulo / 2) {
      InFlight& f = *in_flight_;
      f.frame.seq = c::seq_next(e.frame.seq);
      next_seq_ = c::seq_next(f.frame.seq);
      f.bytes = format(f.frame).value_or(f.bytes);
      f.resend_now = true;
      ++counters_.resyncs;
      ev.kind = EchoKind::Resync;
      return ev;
    }
  }
  ev.kind = EchoKind::Late;
  ++counters_.late;
  return ev;
}

std::vector<Report> Client::take_reports() {
  std::vector<Report> out;
  out.swap(reports_);
  return out;
}

}  // namespace ap::xy_client
