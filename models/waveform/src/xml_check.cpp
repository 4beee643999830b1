// A small XML reader for well-formedness checks of generated files (see svg.hpp). Not a full
// XML 1.0 parser: no DTDs, CDATA or processing instructions other than the prolog.
#include <cctype>

#include "models/waveform/svg.hpp"

namespace ap::model::waveform {
namespace {

class Reader {
 public:
  explicit Reader(std::string_view s) : s_(s) {}

  XmlElement document() {
    skip_misc(true);
    if (!starts("<")) {
      fail("no root element");
    }
    XmlElement root = element();
    skip_misc(false);
    if (pos_ != s_.size()) {
      fail("content after the root element");
    }
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw XmlError("xml: " + what + " at offset " + std::to_string(pos_));
  }
  bool starts(std::string_view p) const { return s_.substr(pos_, p.size()) == p; }
  void skip_ws() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_])) != 0) ++pos_;
  }
  void skip_misc(bool allow_prolog) {
    for (;;) {
      skip_ws();
      if (allow_prolog && starts("<?xml")) {
        const std::size_t e = s_.find("?>", pos_);
        if (e == std::string_view::npos) fail("unterminated prolog");
        pos_ = e + 2;
        allow_prolog = false;
      } else if (starts("<!--")) {
        comment();
      } else {
        return;
      }
    }
  }
  void comment() {
    const std::size_t e = s_.find("-->", pos_ + 4);
    if (e == std::string_view::npos) fail("unterminated comment");
    pos_ = e + 3;
  }
  static bool name_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.' || c == ':';
  }
  std::string name() {
    const std::size_t b = pos_;
    if (pos_ >= s_.size() || !(std::isalpha(static_cast<unsigned char>(s_[pos_])) != 0 || s_[pos_] == '_')) {
      fail("bad name");
    }
    while (pos_ < s_.size() && name_char(s_[pos_])) ++pos_;
    return std::string(s_.substr(b, pos_ - b));
  }
  std::string decode(std::string_view raw) const {
    std::string o;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '<') fail("'<' in character data or attribute");
      if (raw[i] != '&') {
        o += raw[i];
        continue;
      }
      const std::size_t semi = raw.find(';', i);
      if (semi == std::string_view::npos) fail("unterminated entity");
      const std::string_view ent = raw.substr(i + 1, semi - i - 1);
      if (ent == "amp") o += '&';
      else if (ent == "lt") o += '<';
      else if (ent == "gt") o += '>';
      else if (ent == "quot") o += '"';
      else if (ent == "apos") o += '\'';
      else if (ent.size() > 1 && ent[0] == '#') o += '?';
      else fail("unknown entity &" + std::string(ent) + ";");
      i = semi;
    }
    return o;
  }
  XmlElement element() {
    ++pos_;   // '<'
    XmlElement el;
    el.name = name();
    for (;;) {
      const std::size_t before = pos_;
      skip_ws();
      if (starts("/>")) {
        pos_ += 2;
        return el;
      }
      if (starts(">")) {
        ++pos_;
        break;
      }
      if (pos_ == before) fail("expected whitespace before an attribute");
      const std::string an = name();
      skip_ws();
      if (!starts("=")) fail("attribute without '='");
      ++pos_;
      skip_ws();
      if (pos_ >= s_.size() || (s_[pos_] != '"' && s_[pos_] != '\'')) fail("unquoted attribute value");
      const char q = s_[pos_++];
      const std::size_t e = s_.find(q, pos_);
      if (e == std::string_view::npos) fail("unterminated attribute value");
      if (!el.attrs.emplace(an, decode(s_.substr(pos_, e - pos_))).second) fail("duplicate attribute " + an);
      pos_ = e + 1;
    }
    for (;;) {
      const std::size_t lt = s_.find('<', pos_);
      if (lt == std::string_view::npos) fail("unclosed element <" + el.name + ">");
      el.text += decode(s_.substr(pos_, lt - pos_));
      pos_ = lt;
      if (starts("<!--")) {
        comment();
      } else if (starts("</")) {
        pos_ += 2;
        const std::string closing = name();
        skip_ws();
        if (closing != el.name) fail("</" + closing + "> closes <" + el.name + ">");
        if (!starts(">")) fail("bad closing tag");
        ++pos_;
        return el;
      } else if (starts("<?") || starts("<!")) {
        fail("unsupported markup");
      } else {
        el.children.push_back(element());
      }
    }
  }

  std::string_view s_;
  std::size_t pos_ = 0;
};

void collect(const XmlElement& e, std::string_view name, std::vector<const XmlElement*>& out) {
  for (const XmlElement& c : e.children) {
    if (c.name == name) out.push_back(&c);
    collect(c, name, out);
  }
}

}  // namespace

std::vector<const XmlElement*> XmlElement::find_all(std::string_view element) const {
  std::vector<const XmlElement*> out;
  collect(*this, element, out);
  return out;
}

XmlElement parse_xml(std::string_view text) { return Reader(text).document(); }

}  // namespace ap::model::waveform
