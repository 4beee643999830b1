// parse_vcd and the UART / SPI decoders (see vcd.hpp).
#include <algorithm>
#include <cmath>
#include <istream>
#include <iterator>
#include <map>
#include <sstream>

#include "models/waveform/vcd.hpp"

namespace ap::model::waveform {
namespace {

class Tokens {
 public:
  explicit Tokens(std::istream& in) : in_(in) {}
  bool next(std::string& tok) {
    tok.clear();
    return static_cast<bool>(in_ >> tok);
  }
  std::string need(const char* what) {
    std::string t;
    if (!next(t)) {
      throw VcdParseError(std::string("vcd: unexpected end of file, expected ") + what);
    }
    return t;
  }
  // Everything up to the next "$end" token.
  std::vector<std::string> until_end(const char* section) {
    std::vector<std::string> out;
    for (;;) {
      std::string t = need("$end");
      if (t == "$end") {
        return out;
      }
      if (t.size() > 1 && t[0] == '$') {
        throw VcdParseError("vcd: " + t + " inside " + section + " (missing $end)");
      }
      out.push_back(t);
    }
  }

 private:
  std::istream& in_;
};

bool is_binary(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return c == '0' || c == '1' || c == 'x' || c == 'X' || c == 'z' || c == 'Z';
  });
}

std::uint64_t parse_u64(const std::string& s, const char* what) {
  if (s.empty() || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    throw VcdParseError(std::string("vcd: bad ") + what + " '" + s + "'");
  }
  return std::stoull(s);
}

}  // namespace

const VcdDoc::Var* VcdDoc::find(std::string_view scope, std::string_view name) const {
  for (const Var& v : vars) {
    if (v.scope == scope && v.name == name) {
      return &v;
    }
  }
  return nullptr;
}

std::vector<std::pair<std::uint64_t, char>> VcdDoc::trace(std::string_view id) const {
  std::vector<std::pair<std::uint64_t, char>> out;
  for (const Change& c : changes) {
    if (c.id == id) {
      out.emplace_back(c.t, c.value.empty() ? 'x' : c.value.back());
    }
  }
  return out;
}

VcdDoc parse_vcd(std::string_view text) {
  std::istringstream in{std::string(text)};
  return parse_vcd(in);
}

VcdDoc parse_vcd(std::istream& in) {
  VcdDoc doc;
  Tokens tk(in);
  std::vector<std::string> scope;
  std::map<std::string, unsigned, std::less<>> widths;
  bool defs_done = false;
  bool have_time = false;
  bool in_dump = false;
  std::uint64_t now = 0;
  std::string tok;
  auto join_scope = [&] {
    std::string s;
    for (const std::string& p : scope) {
      s += s.empty() ? p : "." + p;
    }
    return s;
  };
  auto add_change = [&](std::string value, std::string id) {
    if (!defs_done || !have_time) {
      throw VcdParseError("vcd: value change before $enddefinitions or before the first #time");
    }
    auto w = widths.find(id);
    if (w == widths.end()) {
      throw VcdParseError("vcd: value for undeclared id '" + id + "'");
    }
    if (!is_binary(value) || value.size() > w->second || (w->second == 1 && value.size() != 1)) {
      throw VcdParseError("vcd: value '" + value + "' does not fit id '" + id + "'");
    }
    doc.changes.push_back(VcdDoc::Change{now, std::move(id), std::move(value)});
  };
  while (tk.next(tok)) {
    if (!defs_done) {
      if (tok == "$date" || tok == "$version" || tok == "$comment") {
        tk.until_end(tok.c_str());
      } else if (tok == "$timescale") {
        const auto parts = tk.until_end("$timescale");
        for (const std::string& p : parts) {
          doc.timescale += p;
        }
        if (doc.timescale.empty()) {
          throw VcdParseError("vcd: empty $timescale");
        }
      } else if (tok == "$scope") {
        const auto parts = tk.until_end("$scope");
        if (parts.size() != 2) {
          throw VcdParseError("vcd: $scope needs a type and a name");
        }
        scope.push_back(parts[1]);
      } else if (tok == "$upscope") {
        if (!tk.until_end("$upscope").empty() || scope.empty()) {
          throw VcdParseError("vcd: unbalanced $upscope");
        }
        scope.pop_back();
      } else if (tok == "$var") {
        const auto parts = tk.until_end("$var");
        if (parts.size() < 4) {
          throw VcdParseError("vcd: $var needs type, width, id and name");
        }
        VcdDoc::Var v;
        v.type = parts[0];
        v.width = static_cast<unsigned>(parse_u64(parts[1], "width"));
        v.id = parts[2];
        v.name = parts[3];
        v.scope = join_scope();
        if (v.width == 0 || !widths.emplace(v.id, v.width).second) {
          throw VcdParseError("vcd: id '" + v.id + "' declared twice or with width 0");
        }
        doc.vars.push_back(std::move(v));
      } else if (tok == "$enddefinitions") {
        if (!tk.until_end("$enddefinitions").empty() || !scope.empty()) {
          throw VcdParseError("vcd: $enddefinitions with open scopes");
        }
        if (doc.timescale.empty()) {
          throw VcdParseError("vcd: no $timescale");
        }
        defs_done = true;
      } else {
        throw VcdParseError("vcd: unexpected '" + tok + "' in the header");
      }
      continue;
    }
    if (tok[0] == '#') {
      const std::uint64_t t = parse_u64(tok.substr(1), "time");
      if (have_time && t <= now) {
        throw VcdParseError("vcd: time " + tok + " does not increase");
      }
      now = t;
      have_time = true;
    } else if (tok == "$dumpvars" || tok == "$dumpall" || tok == "$dumpon" || tok == "$dumpoff") {
      if (in_dump) {
        throw VcdParseError("vcd: nested " + tok);
      }
      in_dump = true;
    } else if (tok == "$end") {
      if (!in_dump) {
        throw VcdParseError("vcd: stray $end");
      }
      in_dump = false;
    } else if (tok == "$comment") {
      tk.until_end("$comment");
    } else if (tok[0] == 'b' || tok[0] == 'B') {
      add_change(tok.substr(1), tk.need("id"));
    } else if (tok[0] == 'r' || tok[0] == 'R') {
      throw VcdParseError("vcd: real values are not produced by axisproof");
    } else if (std::string("01xXzZ").find(tok[0]) != std::string::npos) {
      if (tok.size() < 2) {
        throw VcdParseError("vcd: scalar change without id");
      }
      add_change(tok.substr(0, 1), tok.substr(1));
    } else {
      throw VcdParseError("vcd: unexpected '" + tok + "'");
    }
  }
  if (!defs_done) {
    throw VcdParseError("vcd: no $enddefinitions");
  }
  if (in_dump) {
    throw VcdParseError("vcd: unterminated $dumpvars");
  }
  return doc;
}

namespace {

// Level of a trace (sorted by time) at time t: the last change at or before t. Binary search, so
// decoding a long run stays O(n log n).
char level_at(const std::vector<std::pair<std::uint64_t, char>>& tr, double t) {
  const auto it = std::upper_bound(tr.begin(), tr.end(), t, [](double tt, const std::pair<std::uint64_t, char>& c) {
    return tt < static_cast<double>(c.first);
  });
  return it == tr.begin() ? 'x' : std::prev(it)->second;
}

}  // namespace

std::vector<std::uint8_t> decode_uart(const std::vector<std::pair<std::uint64_t, char>>& line, std::uint32_t baud) {
  std::vector<std::uint8_t> out;
  const double bit = 1e9 / baud;
  double busy_until = -1.0;
  char prev = '1';
  for (const auto& [t, v] : line) {
    const double tt = static_cast<double>(t);
    if (prev == '1' && v == '0' && tt > busy_until) {
      if (level_at(line, tt + 0.5 * bit) != '0') {
        throw VcdParseError("uart: glitch instead of a start bit at " + std::to_string(t));
      }
      std::uint8_t b = 0;
      for (int k = 0; k < 8; ++k) {
        if (level_at(line, tt + (1.5 + k) * bit) == '1') {
          b = static_cast<std::uint8_t>(b | (1U << k));
        }
      }
      if (level_at(line, tt + 9.5 * bit) != '1') {
        throw VcdParseError("uart: framing error (stop bit low) at " + std::to_string(t));
      }
      out.push_back(b);
      busy_until = tt + 9.5 * bit;
    }
    prev = v;
  }
  return out;
}

std::vector<SpiTransfer> decode_spi(const VcdDoc& doc, std::string_view cs_id, bool cpol, bool cpha) {
  const VcdDoc::Var* sck = doc.find("board.spi", "SCK");
  const VcdDoc::Var* mosi = doc.find("board.spi", "MOSI");
  const VcdDoc::Var* miso = doc.find("board.spi", "MISO");
  if (sck == nullptr || mosi == nullptr || miso == nullptr) {
    throw VcdParseError("spi: board.spi.SCK/MOSI/MISO missing");
  }
  const auto cs = doc.trace(cs_id);
  const auto clk = doc.trace(sck->id);
  const auto mo = doc.trace(mosi->id);
  const auto mi = doc.trace(miso->id);
  const char sample_level = cpol == cpha ? '1' : '0';   // rising edge for modes 0 and 3
  std::vector<SpiTransfer> out;
  for (std::size_t i = 0; i < cs.size(); ++i) {
    if (cs[i].second != '0') {
      continue;
    }
    const std::uint64_t start = cs[i].first;
    const std::uint64_t end = i + 1 < cs.size() ? cs[i + 1].first : ~std::uint64_t{0};
    SpiTransfer tr{start, {}, {}};
    unsigned nbits = 0;
    std::uint8_t bo = 0;
    std::uint8_t bi = 0;
    char prev = level_at(clk, static_cast<double>(start));
    // Only the clock edges strictly inside (start, end): binary search for the first one.
    auto first = std::upper_bound(clk.begin(), clk.end(), start,
                                  [](std::uint64_t tt, const std::pair<std::uint64_t, char>& c) { return tt < c.first; });
    for (auto it = first; it != clk.end() && it->first < end; ++it) {
      const auto& [t, v] = *it;
      if (v == sample_level && prev != v) {
        const double ts = static_cast<double>(t);
        bo = static_cast<std::uint8_t>((bo << 1) | (level_at(mo, ts) == '1' ? 1 : 0));
        bi = static_cast<std::uint8_t>((bi << 1) | (level_at(mi, ts) == '1' ? 1 : 0));
        if (++nbits % 8 == 0) {
          tr.mosi.push_back(bo);
          tr.miso.push_back(bi);
        }
      }
      prev = v;
    }
    (void)cpol;
    out.push_back(std::move(tr));
  }
  return out;
}

}  // namespace ap::model::waveform
