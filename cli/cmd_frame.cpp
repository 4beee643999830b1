// axisproof frame: decode, encode and document the frames of a profile's wire codec
// (each profile documents its own frames under docs/; docs/profiles.md lists them).
//   frame decode [--profile P] [FRAME...]   each argument is one frame; without arguments stdin
//                                           is a byte stream (a capture) cut into frames
//   frame encode [--profile P] TOKEN...     readable form, e.g. x=jog:+:fast y=goto:20000 sub=battery
//   frame doc [--profile P]                 the ID tables as markdown (docs/protocol.md carries them)
// Exit 0 when every input decoded (encoded), 1 otherwise; usage errors exit 2 (main.cpp).
#include <cstdio>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "cli.hpp"
#include "profile.hpp"

namespace ap::cli {

void add_frame(CLI::App& app) {
  auto* sub = app.add_subcommand("frame", "Encode and decode a profile's protocol frames (docs/protocol.md)");
  sub->require_subcommand(1, 1);

  static std::vector<std::string> frames;
  static std::string decode_profile;
  auto* decode = sub->add_subcommand("decode", "Decode frames given as arguments, or a byte stream on stdin");
  decode->add_option("frames", frames, "Frames, one per argument (quote them); none: read stdin");
  add_profile_option(decode, decode_profile);
  decode->final_callback([] {
    const Profile* p = find_profile(decode_profile);
    if (p->decode_frames == nullptr || p->decode_stream == nullptr) {
      std::fprintf(stderr, "axisproof frame decode: profile %s has no wire protocol (%.*s)\n", decode_profile.c_str(),
                   static_cast<int>(p->seed.size()), p->seed.data());
      exit_status() = 2;
      return;
    }
    bool ok = true;
    if (frames.empty()) {
      const std::string data((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
      ok = p->decode_stream(data);
    } else {
      ok = p->decode_frames(frames);
    }
    exit_status() = ok ? 0 : 1;
  });

  static std::vector<std::string> tokens;
  static std::string encode_profile;
  auto* encode = sub->add_subcommand("encode", "Build a command frame, e.g. x=jog:+:fast y=goto:20000 sub=battery");
  encode->add_option("tokens", tokens, "seq=N x=KEY[:DATA] y=KEY[:DATA] sub=KEY[:ARG] (keys: axisproof frame doc)")
      ->required();
  add_profile_option(encode, encode_profile);
  encode->final_callback([] {
    const Profile* p = find_profile(encode_profile);
    if (p->encode == nullptr) {
      std::fprintf(stderr, "axisproof frame encode: profile %s has no readable command form\n", encode_profile.c_str());
      exit_status() = 1;
      return;
    }
    exit_status() = p->encode(tokens);
  });

  static std::string doc_profile;
  auto* doc = sub->add_subcommand("doc", "Print the command, status, subscriber and error tables (markdown)");
  add_profile_option(doc, doc_profile);
  doc->final_callback([] {
    const Profile* p = find_profile(doc_profile);
    if (p->doc == nullptr) {
      std::fprintf(stderr, "axisproof frame doc: profile %s has no generated tables\n", doc_profile.c_str());
      exit_status() = 1;
      return;
    }
    p->doc();
    exit_status() = 0;
  });
}

}  // namespace ap::cli
