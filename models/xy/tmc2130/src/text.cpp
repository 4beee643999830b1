#include "models/xy/tmc2130/text.hpp"

#include <cctype>
#include <cstdio>

#include "core/xy/tmc2130/fields.hpp"
#include "core/xy/tmc2130/regmap.hpp"

namespace ap::model::xy_tmc2130 {

namespace chip = ap::xy_tmc2130;

namespace {

std::string hex(std::uint32_t v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, static_cast<unsigned>(v));
  return buf;
}

std::string range(const chip::FieldInfo& f) {
  return std::to_string(f.min) + ".." + std::to_string(f.max);
}

std::string fields_of(std::uint32_t word, const chip::RegisterInfo& r) {
  std::string out;
  for (std::size_t i = r.first_field; i < std::size_t{r.first_field} + r.field_count; ++i) {
    const auto& f = chip::kFields[i];
    if (!out.empty()) out += ' ';
    out += std::string(f.name) + "=" + std::to_string(chip::field_get(word, f.field));
  }
  const std::uint32_t stray = word & ~chip::implemented_mask(r.reg);
  if (stray != 0) out += " (unimplemented bits " + hex(stray, 8) + ")";
  return out;
}

}  // namespace

std::string register_map(MapFormat format) {
  std::string out;
  if (format == MapFormat::Csv) {
    out = "register,address,access,field,mask,shift,width,signed\n";
  } else if (format == MapFormat::Markdown) {
    out = "| register | address | access | reset | field | mask | shift | width | signed | range |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
  }
  for (const auto& r : chip::kRegisters) {
    if (format == MapFormat::Text) {
      out += std::string(r.name) + " " + hex(chip::address(r.reg), 2) + " " +
             std::string(chip::access_name(r.access)) + " reset " + hex(r.reset, 8) + "\n";
    }
    for (std::size_t i = r.first_field; i < std::size_t{r.first_field} + r.field_count; ++i) {
      const auto& f = chip::kFields[i];
      const std::string sgn = f.is_signed ? "yes" : "no";
      switch (format) {
        case MapFormat::Csv:
          out += std::string(r.name) + "," + hex(chip::address(r.reg), 2) + "," +
                 std::string(chip::access_name(r.access)) + "," + std::string(f.name) + "," +
                 hex(f.mask, 8) + "," + std::to_string(f.shift) + "," + std::to_string(f.width) +
                 "," + sgn + "\n";
          break;
        case MapFormat::Markdown:
          out += "| " + std::string(r.name) + " | " + hex(chip::address(r.reg), 2) + " | " +
                 std::string(chip::access_name(r.access)) + " | " + hex(r.reset, 8) + " | " +
                 std::string(f.name) + " | " + hex(f.mask, 8) + " | " + std::to_string(f.shift) +
                 " | " + std::to_string(f.width) + " | " + sgn + " | " + range(f) + " |\n";
          break;
        case MapFormat::Text: {
          char line[128];
          std::snprintf(line, sizeof line, "  %-20s mask %s shift %2u width %2u %-8s %s\n",
                        std::string(f.name).c_str(), hex(f.mask, 8).c_str(), unsigned{f.shift},
                        unsigned{f.width}, f.is_signed ? "signed" : "unsigned", range(f).c_str());
          out += line;
          break;
        }
      }
    }
  }
  return out;
}

std::string decode_datagram(const chip::Datagram& d, bool as_reply, std::optional<std::uint8_t> reg) {
  std::string out;
  if (as_reply) {
    const chip::Reply rep = chip::decode_reply(d);
    const auto& s = rep.status;
    out = "SPI_STATUS " + hex(d[0], 2) + ": reset_flag=" + std::to_string(s.reset_flag) +
          " driver_error=" + std::to_string(s.driver_error) + " sg2=" + std::to_string(s.sg2) +
          " standstill=" + std::to_string(s.standstill) + "\n";
    out += "data " + hex(rep.data, 8) + " (latched by the previous access)\n";
    if (reg) {
      if (const auto r = chip::find_register(*reg)) {
        out += std::string(chip::info(*r).name) + ": " + fields_of(rep.data, chip::info(*r)) + "\n";
      } else {
        out += "unknown register " + hex(*reg, 2) + "\n";
      }
    }
    return out;
  }
  const chip::Request req = chip::decode_request(d);
  const auto r = chip::find_register(req.address);
  const std::string name = r ? std::string(chip::info(*r).name) : "unknown register";
  out = std::string(req.write ? "write " : "read ") + name + " (" + hex(req.address, 2) + ")";
  if (!req.write) return out + ": data bits ignored by the chip, reply arrives with the next datagram\n";
  out += " data " + hex(req.data, 8) + "\n";
  if (r) {
    out += "  " + fields_of(req.data, chip::info(*r)) + "\n";
    if (!chip::writable(*r)) out += "  warning: " + name + " is not writable; the chip ignores this\n";
  }
  return out;
}

std::optional<chip::Datagram> parse_datagram(const std::vector<std::string>& words) {
  std::string digits;
  for (const auto& w : words) {
    std::size_t i = 0;
    while (i < w.size()) {
      if (w[i] == ',' || w[i] == ' ' || w[i] == ':') {
        ++i;
        continue;
      }
      if (w[i] == '0' && i + 1 < w.size() && (w[i + 1] == 'x' || w[i + 1] == 'X')) {
        i += 2;
        std::string tok;
        while (i < w.size() && std::isxdigit(static_cast<unsigned char>(w[i]))) tok += w[i++];
        if (tok.empty() || tok.size() > 2) return std::nullopt;
        if (tok.size() == 1) tok = "0" + tok;
        digits += tok;
        continue;
      }
      std::string tok;
      while (i < w.size() && std::isxdigit(static_cast<unsigned char>(w[i]))) tok += w[i++];
      if (tok.empty()) return std::nullopt;
      if (tok.size() == 1) tok = "0" + tok;
      if (tok.size() % 2 != 0) return std::nullopt;
      digits += tok;
    }
  }
  if (digits.size() != 10) return std::nullopt;
  chip::Datagram d{};
  for (std::size_t k = 0; k < 5; ++k) {
    d[k] = static_cast<std::uint8_t>(std::stoul(digits.substr(2 * k, 2), nullptr, 16));
  }
  return d;
}

}  // namespace ap::model::xy_tmc2130
