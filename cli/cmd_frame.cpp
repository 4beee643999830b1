// axisproof frame: encode and decode protocol frames (docs/protocol.md).
//   frame decode [FRAME...]   each argument is one frame; without arguments stdin is a
//                             byte stream (a capture) cut into frames by the stream framer
//   frame encode TOKEN...     readable form, e.g. x=jog:+:fast y=goto:20000 sub=battery
//   frame doc                 the ID tables as markdown (docs/protocol.md carries them)
// Exit 0 when every input decoded (encoded), 1 otherwise; usage errors exit 2 (main.cpp).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "cli.hpp"
#include "pc/client/client.hpp"
#include "pc/client/doc_tables.hpp"
#include "pc/client/readable.hpp"
#include "protocol/codec/layout.hpp"
#include "core/frame/command_codec.hpp"
#include "core/frame/echo_codec.hpp"
#include "core/frame/stream_framer.hpp"

namespace ap::cli {

namespace {

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

std::string printable(const std::string& s) {
  std::string out;
  for (const char c : s) {
    const auto ch = static_cast<unsigned char>(c);
    if (ch >= 0x20 && ch < 0x7F) {
      out += static_cast<char>(ch);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", ch);
      out += hex;
    }
  }
  return out;
}

// One frame given whole: its start character says which kind it is meant to be.
bool decode_one(const std::string& text, const std::string& label) {
  if (!text.empty() && text[0] == codec::kEchoStart) {
    frame::EchoFrame e;
    const auto r = frame::parse_echo(bytes_of(text), e);
    if (!r.ok()) {
      std::printf("%s: REJECTED %s\n  bytes: %s\n", label.c_str(), client::describe(r).c_str(), printable(text).c_str());
      return false;
    }
    std::printf("%s: OK %s", label.c_str(), client::describe(e).c_str());
    return true;
  }
  frame::CommandFrame c;
  const auto r = frame::parse_command(bytes_of(text), c);
  if (!r.ok()) {
    std::printf("%s: REJECTED %s\n  bytes: %s\n", label.c_str(), client::describe(r).c_str(), printable(text).c_str());
    return false;
  }
  std::printf("%s: OK %s", label.c_str(), client::describe(c).c_str());
  return true;
}

struct Report {
  std::uint32_t offset;
  std::string text;
  bool ok;
};

// A capture may hold commands, echoes, whitespace between them and garbage; every
// non-whitespace byte that is in no frame is reported, so nothing is silently skipped.
bool decode_stream(const std::string& data) {
  std::vector<Report> reports;
  std::vector<bool> covered(data.size(), false);
  const auto cover = [&](std::uint32_t at, std::size_t n) {
    for (std::size_t i = at; i < at + n && i < covered.size(); ++i) covered[i] = true;
  };
  frame::CommandFramer commands;
  commands.feed(bytes_of(data), [&](const frame::CommandFramer::Event& e) {
    cover(e.stream_offset, e.length);
    const std::string where = "byte " + std::to_string(e.stream_offset);
    reports.push_back({e.stream_offset,
                       e.rejection.ok() ? where + ": OK " + client::describe(e.frame)
                                        : where + ": REJECTED command, " + client::describe(e.rejection) + "\n",
                       e.rejection.ok()});
  });
  frame::EchoFramer echoes;
  echoes.feed(bytes_of(data), [&](const frame::EchoFramer::Event& e) {
    cover(e.stream_offset, e.length);
    const std::string where = "byte " + std::to_string(e.stream_offset);
    reports.push_back({e.stream_offset,
                       e.rejection.ok() ? where + ": OK " + client::describe(e.frame)
                                        : where + ": REJECTED echo, " + client::describe(e.rejection) + "\n",
                       e.rejection.ok()});
  });
  for (const auto pending : {commands.pending(), echoes.pending()}) {
    if (pending == 0) continue;
    const auto at = static_cast<std::uint32_t>(data.size() - pending);
    cover(at, pending);
    reports.push_back({at, "byte " + std::to_string(at) + ": REJECTED incomplete frame at end of input (" +
                               std::to_string(pending) + " bytes)\n", false});
  }
  for (std::size_t i = 0; i < data.size();) {
    const bool space = data[i] == ' ' || data[i] == '\n' || data[i] == '\r' || data[i] == '\t';
    if (covered[i] || space) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < data.size() && !covered[j]) ++j;
    reports.push_back({static_cast<std::uint32_t>(i),
                       "byte " + std::to_string(i) + ": GARBAGE " + printable(data.substr(i, j - i)) + "\n", false});
    i = j;
  }
  std::stable_sort(reports.begin(), reports.end(), [](const Report& a, const Report& b) { return a.offset < b.offset; });
  bool all_ok = true;
  for (const auto& r : reports) {
    std::fputs(r.text.c_str(), stdout);
    all_ok = all_ok && r.ok;
  }
  const auto accepted = commands.counters().accepted_frames + echoes.counters().accepted_frames;
  std::printf("%u frame(s) decoded, %zu problem(s)\n", accepted,
              static_cast<std::size_t>(std::count_if(reports.begin(), reports.end(), [](const Report& r) { return !r.ok; })));
  return all_ok && accepted > 0;
}

}  // namespace

void add_frame(CLI::App& app) {
  auto* sub = app.add_subcommand("frame", "Encode and decode protocol frames (docs/protocol.md)");
  sub->require_subcommand(1, 1);

  static std::vector<std::string> frames;
  auto* decode = sub->add_subcommand("decode", "Decode frames given as arguments, or a byte stream on stdin");
  decode->add_option("frames", frames, "Frames, one per argument (quote them); none: read stdin");
  decode->final_callback([] {
    bool ok = true;
    if (frames.empty()) {
      const std::string data((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
      ok = decode_stream(data);
    } else {
      for (std::size_t i = 0; i < frames.size(); ++i) ok = decode_one(frames[i], "frame " + std::to_string(i + 1)) && ok;
    }
    exit_status() = ok ? 0 : 1;
  });

  static std::vector<std::string> tokens;
  auto* encode = sub->add_subcommand("encode", "Build a command frame, e.g. x=jog:+:fast y=goto:20000 sub=battery");
  encode->add_option("tokens", tokens, "seq=N x=KEY[:DATA] y=KEY[:DATA] sub=KEY[:ARG] (keys: axisproof frame doc)")
      ->required();
  encode->final_callback([] {
    std::string text;
    for (const auto& t : tokens) text += t + " ";
    frame::CommandFrame f;
    const auto err = client::parse_readable(text, f);
    if (!err.empty()) {
      std::fprintf(stderr, "axisproof frame encode: %s\n", err.c_str());
      exit_status() = 1;
      return;
    }
    const auto bytes = client::format(f);
    if (!bytes) {
      std::fprintf(stderr, "axisproof frame encode: frame does not validate\n");
      exit_status() = 1;
      return;
    }
    std::printf("%s\n", bytes->c_str());
    exit_status() = 0;
  });

  auto* doc = sub->add_subcommand("doc", "Print the command, status, subscriber and error tables (markdown)");
  doc->final_callback([] {
    std::fputs(client::all_tables_md().c_str(), stdout);
    exit_status() = 0;
  });
}

}  // namespace ap::cli
