// The shared plumbing of the profiles' scenario languages (sim/scenario_text.hpp).
#include "sim/scenario_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace ap::sim::text {

bool compare(std::int64_t got, Op op, std::int64_t want) {
  switch (op) {
    case Op::Eq: return got == want;
    case Op::Ne: return got != want;
    case Op::Lt: return got < want;
    case Op::Le: return got <= want;
    case Op::Gt: return got > want;
    case Op::Ge: return got >= want;
  }
  return false;
}

bool compare_within(double got, Op op, double want, double tol, double slack) {
  switch (op) {
    case Op::Eq: return std::abs(got - want) <= tol + slack;
    case Op::Ne: return std::abs(got - want) > tol + slack;
    case Op::Lt: return got < want + tol;
    case Op::Le: return got <= want + tol + slack;
    case Op::Gt: return got > want - tol;
    case Op::Ge: return got >= want - tol - slack;
  }
  return false;
}

const char* op_text(Op op) {
  switch (op) {
    case Op::Eq: return "==";
    case Op::Ne: return "!=";
    case Op::Lt: return "<";
    case Op::Le: return "<=";
    case Op::Gt: return ">";
    case Op::Ge: return ">=";
  }
  return "?";
}

std::optional<Op> op_of(std::string_view w) {
  for (const Op op : {Op::Eq, Op::Ne, Op::Lt, Op::Le, Op::Gt, Op::Ge}) {
    if (w == op_text(op)) return op;
  }
  return std::nullopt;
}

bool parse_time(const std::string& number, const std::string& unit, std::int64_t& us, const TimeRules& rules) {
  std::int64_t scale = 0;
  if (unit == "s") scale = 1'000'000;
  else if (unit == "ms") scale = 1'000;
  else if (unit == "us") scale = 1;
  else return false;
  if (number.empty() || number.size() > rules.max_chars || number.find_first_of("0123456789") == std::string::npos) {
    return false;
  }
  // Exact decimal arithmetic: each digit after the point is worth a tenth of the one before;
  // a non-zero digit worth less than 1 us makes the time finer than 1 us.
  std::int64_t whole = 0, frac_us = 0, place = scale;
  bool dot = false, finer = false, huge = false;
  for (const char c : number) {
    if (c == '.' && !dot) {
      dot = true;
    } else if (std::isdigit(static_cast<unsigned char>(c)) != 0) {
      const int d = c - '0';
      if (dot) {
        if (place % 10 == 0) {
          place /= 10;
          frac_us += d * place;
        } else if (d != 0) {
          finer = true;
        }
      } else if (whole > (std::numeric_limits<std::int64_t>::max() - 9) / 10) {
        huge = true;
      } else {
        whole = whole * 10 + d;
      }
    } else {
      return false;
    }
  }
  if (finer || huge || whole > rules.max_us / scale) return false;
  us = whole * scale + frac_us;
  return us <= rules.max_us;  // beyond it: a typo, not a scenario
}

namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::vector<Token> tokenize(const std::string& s, const std::string& file, int n, const Dialect& dialect) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == '#') {
      break;
    } else if (c == '"') {
      Token t{"", true};
      ++i;
      for (;;) {
        if (i >= s.size()) throw ParseError(file, n, "unterminated string");
        const char d = s[i++];
        if (d == '"') break;
        if (d != '\\') {
          t.text += d;
          continue;
        }
        if (i >= s.size()) throw ParseError(file, n, "unterminated string");
        if (!dialect.full_escapes) {
          if (s[i] != '"' && s[i] != '\\') throw ParseError(file, n, "a string escapes only \\\" and \\\\");
          t.text += s[i++];
          continue;
        }
        const char e = s[i++];
        switch (e) {
          case '"': t.text += '"'; break;
          case '\\': t.text += '\\'; break;
          case 'r': t.text += '\r'; break;
          case 'n': t.text += '\n'; break;
          case 't': t.text += '\t'; break;
          case 'x': {
            const int hi = i < s.size() ? hex_digit(s[i]) : -1;
            const int lo = i + 1 < s.size() ? hex_digit(s[i + 1]) : -1;
            if (hi < 0 || lo < 0) throw ParseError(file, n, "\\x needs two hex digits");
            t.text += static_cast<char>(hi * 16 + lo);
            i += 2;
            break;
          }
          default: throw ParseError(file, n, std::string("unknown escape \\") + e);
        }
      }
      out.push_back(std::move(t));
    } else {
      Token t;
      while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != '\r' && s[i] != '#' && s[i] != '"') t.text += s[i++];
      out.push_back(std::move(t));
    }
  }
  return out;
}

std::string quote(const std::string& s, const Dialect& d) {
  static const char* const kHex = "0123456789abcdef";
  std::string o = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += c;
    } else if (!d.full_escapes) {
      o += c;
    } else if (c == '\r') {
      o += "\\r";
    } else if (c == '\n') {
      o += "\\n";
    } else if (c == '\t') {
      o += "\\t";
    } else if (const auto b = static_cast<unsigned char>(c); b < 0x20 || b == 0x7f) {
      o += "\\x";
      o += kHex[b >> 4];
      o += kHex[b & 0xF];
    } else {
      o += c;
    }
  }
  return o + "\"";
}

std::string shown(const std::string& raw, const Dialect& d) {
  std::string s = raw.substr(raw.find_first_not_of(" \t"));
  if (d.cut_blank_hash) {
    if (const auto hash = s.find(" #"); hash != std::string::npos && s.find('"') == std::string::npos) s.resize(hash);
    return s;
  }
  if (const auto hash = s.find('#'); hash != std::string::npos) s.resize(hash);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.pop_back();
  return s;
}

const Token& Line::next(const char* what) const {
  if (done()) fail(d_.name_at_end ? std::string("expected ") + what + " at the end of the line" : std::string("unexpected end of line"));
  return t_[i_];
}

bool Line::accept(const char* w) {
  if (!peek_is(w)) return false;
  ++i_;
  return true;
}

std::string Line::word(const char* what) {
  const Token& t = next(what);
  if (t.quoted) fail(std::string("expected ") + what + ", got a string");
  ++i_;
  return t.text;
}

void Line::expect_word(const char* w) {
  const std::string got = word(w);
  if (got != w) fail(std::string("expected '") + w + "', got '" + got + "'");
}

std::string Line::string(const char* what) {
  const Token& t = next(what);
  if (!t.quoted) fail(std::string("expected ") + what + " as a \"string\", got '" + t.text + "'");
  ++i_;
  return t.text;
}

std::int64_t Line::time() {
  std::string num = word("a time");
  std::string unit;
  const auto split = num.find_first_not_of("0123456789.");
  if (split != std::string::npos && split > 0) {
    unit = num.substr(split);
    num.resize(split);
  } else {
    if (done()) fail("time '" + num + "' needs a unit (s, ms, us)");
    unit = word("a time unit");
  }
  std::int64_t us = 0;
  if (!parse_time(num, unit, us, d_.time)) fail("bad time '" + num + " " + unit + "' (a number and s, ms or us, whole us)");
  return us;
}

Op Line::op() {
  const std::string w = word("a comparison");
  if (const auto op = op_of(w)) return *op;
  fail("unknown comparison '" + w + "' (== != < <= > >=)");
}

void Line::end() const {
  if (!done()) fail("unexpected '" + t_[i_].text + "' at the end of the line");
}

bool valid_name(const std::string& n) {
  return !n.empty() && std::all_of(n.begin(), n.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
}

int each_statement(const std::string& text, const std::string& file, const Dialect& d,
                   const std::function<void(Line&, const std::string&)>& each) {
  std::istringstream in(text);
  std::string raw;
  int n = 0;
  while (std::getline(in, raw)) {
    ++n;
    Line l(file, n, raw, d);
    if (!l.done()) each(l, shown(raw, d));
  }
  return n;
}

bool Header::read(const std::string& kw, Line& l) {
  if (kw == "scenario") {
    if (have_name_) l.fail("a second 'scenario' line");
    name = l.word("the scenario's name");
    if (!valid_name(name)) l.fail("scenario name '" + name + "': letters, digits, _ and - only");
    have_name_ = true;
  } else if (kw == "title") {
    if (have_title_ && l.dialect().one_title) l.fail("a second 'title' line");
    title = l.string("the title");
    have_title_ = true;
  } else if (kw == "duration") {
    if (have_duration_) l.fail("a second 'duration' line");
    duration_us = l.time();
    if (duration_us < 1000 || duration_us % 1000 != 0) l.fail("the duration is whole ms, at least 1 ms");
    have_duration_ = true;
  } else {
    return false;
  }
  l.end();
  return true;
}

void Header::check(const std::string& file, int n) const {
  if (!have_name_) throw ParseError(file, n, "no 'scenario NAME' line");
  if (!have_duration_) throw ParseError(file, n, "no 'duration' line");
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scenario " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace ap::sim::text
