// The plumbing every line-based scenario language of sim/ shares ("Scenario language" in each
// profile's docs/*-sim.md page): words and "strings" split on blanks, `#` comments,
// times with a unit, comparisons, and the "file:line: message" error. Each profile's parser
// keeps only its own statements and quantities; where the languages were written to differ
// (string escapes, the end-of-line message, the time limits, the line shown in the report) a
// Dialect says which, so one implementation serves them all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ap::sim::text {

class ParseError : public std::runtime_error {
 public:
  ParseError(const std::string& file, int line, const std::string& what)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + what), file_(file), line_(line) {}
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] int line() const { return line_; }

 private:
  std::string file_;
  int line_;
};

enum class Op : std::uint8_t { Eq, Ne, Lt, Le, Gt, Ge };
bool compare(std::int64_t got, Op op, std::int64_t want);
// A measured value against a bound: `tol` makes == a band (|got - want| <= tol) and != its
// outside, and widens the inequalities (got < want + tol, got <= want + tol, got > want - tol,
// got >= want - tol); `slack` more is allowed for ==, !=, <= and >= (never for the strict ones),
// so a value exactly on a bound after a unit conversion holds.
bool compare_within(double got, Op op, double want, double tol, double slack);
const char* op_text(Op op);
// "==", "!=", "<", "<=", ">", ">=" -> the comparison; nullopt for any other word.
std::optional<Op> op_of(std::string_view w);

// How long a time's number may be written and how far a run may reach.
struct TimeRules {
  std::size_t max_chars = 15;
  std::int64_t max_us = 86'400'000'000LL;
};

// "10 ms", "0.5 s", "250 us" -> microseconds, in exact decimal arithmetic: whole microseconds
// or false, never a rounded time; false too for a negative, too long or too late time.
bool parse_time(const std::string& number, const std::string& unit, std::int64_t& us, const TimeRules& rules = {});

struct Dialect {
  bool full_escapes = false;  // strings take \r \n \t \xHH besides \" and \\ (else only those two)
  bool name_at_end = false;   // a word missing at the end: "expected X at the end of the line"
                              // (else "unexpected end of line")
  bool cut_blank_hash = false;  // the line shown: cut at " #" unless it holds a string, keep
                                // trailing blanks (else cut at '#', drop trailing blanks)
  bool one_title = false;       // a second `title` line is an error (else the last one counts)
  TimeRules time;
};

struct Token {
  std::string text;
  bool quoted = false;
};

// Words split on blanks; "strings" with the dialect's escapes; `#` outside a string ends the line.
std::vector<Token> tokenize(const std::string& s, const std::string& file, int n, const Dialect& d);

// `s` as a "string" the dialect's tokenizer reads back as `s`: \" and \\ escaped, and in the
// full dialect the control bytes too (\r \n \t, the others \xHH). The plain dialect has no
// escape for a line break: `s` holds none.
std::string quote(const std::string& s, const Dialect& d);

// The statement as written, for the report: without its leading blanks and its comment.
// `raw` holds at least one token.
std::string shown(const std::string& raw, const Dialect& d);

// One line's tokens, read left to right; every error names file:line.
class Line {
 public:
  Line(std::string file, int n, const std::string& raw, const Dialect& d)
      : file_(std::move(file)), n_(n), d_(d), t_(tokenize(raw, file_, n, d)) {}

  [[noreturn]] void fail(const std::string& what) const { throw ParseError(file_, n_, what); }
  [[nodiscard]] bool done() const { return i_ >= t_.size(); }
  [[nodiscard]] bool peek_is(const char* w) const { return !done() && !t_[i_].quoted && t_[i_].text == w; }
  // The next token, left in place; nullptr at the end of the line.
  [[nodiscard]] const Token* peek() const { return done() ? nullptr : &t_[i_]; }
  // Takes the word `w` when it comes next.
  bool accept(const char* w);
  std::string word(const char* what);
  void expect_word(const char* w);
  std::string string(const char* what);
  // A time: "10 ms", "0.5 s", or written together, "10ms".
  std::int64_t time();
  Op op();
  void end() const;
  [[nodiscard]] int number() const { return n_; }
  [[nodiscard]] const Dialect& dialect() const { return d_; }

 private:
  const Token& next(const char* what) const;

  std::string file_;
  int n_;
  Dialect d_;
  std::vector<Token> t_;
  std::size_t i_ = 0;
};

// Letters, digits, _ and - (a scenario's name).
bool valid_name(const std::string& n);

// Every line of `text` that holds a statement, in order: each(line, the statement as shown).
// Returns the number of lines (the line an error about the whole file names).
int each_statement(const std::string& text, const std::string& file, const Dialect& d,
                   const std::function<void(Line&, const std::string&)>& each);

// The statements every language has: `scenario NAME` and `duration T` (once each, whole ms)
// and `title "..."`.
struct Header {
  std::string name;
  std::string title;
  std::int64_t duration_us = 0;

  // Reads the rest of the line when `kw` is scenario, title or duration; false for another.
  bool read(const std::string& kw, Line& l);
  // After the file's last line `n`: the name and the duration were given.
  void check(const std::string& file, int n) const;

 private:
  bool have_name_ = false, have_title_ = false, have_duration_ = false;
};

// The whole file; std::runtime_error "cannot read scenario PATH" when it cannot be opened.
std::string read_file(const std::string& path);

}  // namespace ap::sim::text
