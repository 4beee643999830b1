// axisproof regs: the TMC2130 register map (from the one table in core/xy/tmc2130) and a
// decoder for captured 40-bit datagrams.
#include "cli.hpp"
#include "commands.hpp"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "models/xy/tmc2130/text.hpp"

namespace ap::cli {

namespace {

struct RegsOptions {
  std::string format = "text";
  std::vector<std::string> bytes;
  bool reply = false;
  std::string reg;
};

}  // namespace

void add_regs(CLI::App& app) {
  namespace mt = ap::model::xy_tmc2130;
  auto opt = std::make_shared<RegsOptions>();
  auto* sub = app.add_subcommand("regs", "Print the TMC2130 register map and decode datagrams");
  sub->add_option("--format", opt->format, "text, csv (register,address,access,field,mask,shift,width,signed) or md")
      ->check(CLI::IsMember({"text", "csv", "md"}));
  auto* dec = sub->add_subcommand("decode", "Decode a 5-byte datagram, e.g. 90 00 07 0C 03");
  dec->add_option("bytes", opt->bytes, "Five hex bytes (MOSI unless --reply)")->required();
  dec->add_flag("--reply", opt->reply, "Decode as a MISO reply: SPI_STATUS and latched data");
  dec->add_option("--reg", opt->reg, "With --reply: address of the register the data belongs to (hex)");
  dec->final_callback([opt] {
    const auto d = mt::parse_datagram(opt->bytes);
    if (!d) {
      std::fprintf(stderr, "axisproof regs decode: need exactly 5 hex bytes\n");
      exit_status() = 2;
      return;
    }
    std::optional<std::uint8_t> reg;
    if (!opt->reg.empty()) {
      char* end = nullptr;
      const unsigned long a = std::strtoul(opt->reg.c_str(), &end, 16);
      if (end == opt->reg.c_str() || *end != '\0' || a > 0x7F) {
        std::fprintf(stderr, "axisproof regs decode: --reg wants a hex address 00..7F\n");
        exit_status() = 2;
        return;
      }
      reg = static_cast<std::uint8_t>(a);
    }
    std::fputs(mt::decode_datagram(*d, opt->reply, reg).c_str(), stdout);
    exit_status() = 0;
  });
  sub->final_callback([opt, dec] {
    if (dec->parsed()) return;
    const auto f = opt->format == "csv" ? mt::MapFormat::Csv
                   : opt->format == "md" ? mt::MapFormat::Markdown
                                         : mt::MapFormat::Text;
    std::fputs(mt::register_map(f).c_str(), stdout);
    exit_status() = 0;
  });
}

}  // namespace ap::cli
