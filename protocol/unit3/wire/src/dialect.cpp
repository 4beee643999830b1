#include "protocol/unit3/wire/dialect.hpp"

namespace ap::unit3_wire {

namespace {

constexpr std::uint8_t kDigitsPerSetting = kAxes;  // one digit or sign per axis: D, M, T
constexpr std::size_t kSettingLength = 1 + kDigitsPerSetting + 1;
constexpr std::size_t kBareLength = 2;             // C; G;

Rejection reject(Error e, std::size_t at) { return {e, static_cast<std::uint8_t>(at)}; }
bool is_digit(std::uint8_t b) { return b >= '0' && b <= '9'; }

// Each command's length, fixed by its first byte; 0 for an unknown one.
std::size_t length_of(std::uint8_t first) {
  switch (first) {
    case 'X': case 'Y': case 'Z': return kMaxLine;
    case 'D': case 'M': case 'T': return kSettingLength;
    case 'C': case 'G': return kBareLength;
    default: return 0;
  }
}

// The three per-axis digits of M or T, each at most `max`.
Rejection read_digits(std::span<const std::uint8_t> line, std::uint8_t max, Error too_big,
                      std::array<std::uint8_t, kAxes>& out) {
  for (std::size_t i = 0; i < kAxes; ++i) {
    const std::uint8_t b = line[1 + i];
    if (!is_digit(b)) return reject(Error::BadDigit, 1 + i);
    const auto d = static_cast<std::uint8_t>(b - '0');
    if (d > max) return reject(too_big, 1 + i);
    out[i] = d;
  }
  return {};
}

}  // namespace

const char* error_key(Error e) {
  switch (e) {
    case Error::None: return "none";
    case Error::UnknownCommand: return "unknown_command";
    case Error::BadLength: return "bad_length";
    case Error::BadDigit: return "bad_digit";
    case Error::BadSign: return "bad_sign";
    case Error::ModeOutOfRange: return "mode_out_of_range";
    case Error::ThreadOutOfRange: return "thread_out_of_range";
    case Error::TooLong: return "too_long";
  }
  return "?";
}

Rejection parse(std::span<const std::uint8_t> line, Command& out) {
  if (line.empty()) return reject(Error::BadLength, 0);
  const std::size_t want = length_of(line[0]);
  if (want == 0) return reject(Error::UnknownCommand, 0);
  // The `;` must stand exactly at the command's last position: earlier or later is a byte
  // lost or added on the line.
  if (line.size() != want || line[want - 1] != kEnd) {
    return reject(Error::BadLength, line.size() < want ? line.size() - 1 : want - 1);
  }
  Command c;
  switch (line[0]) {
    case 'X': case 'Y': case 'Z': {
      std::uint64_t v = 0;
      for (std::size_t i = 1; i <= kCountDigits; ++i) {
        if (!is_digit(line[i])) return reject(Error::BadDigit, i);
        v = v * 10U + static_cast<std::uint64_t>(line[i] - '0');  // <= 10^15 - 1: no overflow
      }
      c.kind = Kind::Move;
      c.axis = static_cast<Axis>(line[0] - 'X');
      c.count = v;
      break;
    }
    case 'D':
      for (std::size_t i = 0; i < kAxes; ++i) {
        const std::uint8_t b = line[1 + i];
        if (b != '+' && b != '-') return reject(Error::BadSign, 1 + i);
        c.sign[i] = b == '+' ? std::int8_t{1} : std::int8_t{-1};
      }
      c.kind = Kind::Direction;
      break;
    case 'M':
      if (auto r = read_digits(line, kMaxModeDigit, Error::ModeOutOfRange, c.digit); !r.ok()) return r;
      c.kind = Kind::StepMode;
      break;
    case 'T':
      if (auto r = read_digits(line, kMaxThreadDigit, Error::ThreadOutOfRange, c.digit); !r.ok()) return r;
      c.kind = Kind::Thread;
      break;
    case 'C': c.kind = Kind::Clear; break;
    default: c.kind = Kind::Get; break;  // 'G': length_of admitted nothing else
  }
  out = c;
  return {};
}

std::size_t format(const Command& c, std::span<std::uint8_t, kMaxLine> out) {
  std::array<std::uint8_t, kMaxLine> b{};
  std::size_t n = 0;
  switch (c.kind) {
    case Kind::Move: {
      if (c.count > kMaxCount || static_cast<std::uint8_t>(c.axis) >= kAxes) return 0;
      b[0] = static_cast<std::uint8_t>('X' + static_cast<std::uint8_t>(c.axis));
      std::uint64_t v = c.count;
      for (std::size_t i = kCountDigits; i >= 1; --i) {
        b[i] = static_cast<std::uint8_t>('0' + v % 10U);
        v /= 10U;
      }
      n = kMaxLine;
      break;
    }
    case Kind::Direction:
      b[0] = 'D';
      for (std::size_t i = 0; i < kAxes; ++i) {
        if (c.sign[i] != 1 && c.sign[i] != -1) return 0;
        b[1 + i] = c.sign[i] > 0 ? '+' : '-';
      }
      n = kSettingLength;
      break;
    case Kind::StepMode:
    case Kind::Thread: {
      const bool mode = c.kind == Kind::StepMode;
      b[0] = mode ? 'M' : 'T';
      for (std::size_t i = 0; i < kAxes; ++i) {
        if (c.digit[i] > (mode ? kMaxModeDigit : kMaxThreadDigit)) return 0;
        b[1 + i] = static_cast<std::uint8_t>('0' + c.digit[i]);
      }
      n = kSettingLength;
      break;
    }
    case Kind::Clear: b[0] = 'C'; n = kBareLength; break;
    case Kind::Get: b[0] = 'G'; n = kBareLength; break;
    default: return 0;
  }
  b[n - 1] = kEnd;
  for (std::size_t i = 0; i < n; ++i) out[i] = b[i];
  return n;
}

std::size_t format_report(Axis a, std::int64_t count, std::span<std::uint8_t, kReportLength> out) {
  if (count > kMaxReportCount || count < -kMaxReportCount || static_cast<std::uint8_t>(a) >= kAxes) return 0;
  out[0] = static_cast<std::uint8_t>('X' + static_cast<std::uint8_t>(a));
  out[1] = count < 0 ? '-' : '+';
  auto v = static_cast<std::uint64_t>(count < 0 ? -count : count);  // |count| < 10^18: no overflow
  for (std::size_t i = 1 + kReportDigits; i >= 2; --i) {
    out[i] = static_cast<std::uint8_t>('0' + v % 10U);
    v /= 10U;
  }
  out[kReportLength - 1] = kEnd;
  return kReportLength;
}

std::optional<Report> parse_report(std::span<const std::uint8_t> line) {
  if (line.size() != kReportLength || line[kReportLength - 1] != kEnd) return std::nullopt;
  if (line[0] < 'X' || line[0] > 'Z' || (line[1] != '+' && line[1] != '-')) return std::nullopt;
  std::int64_t v = 0;
  for (std::size_t i = 2; i < 2 + kReportDigits; ++i) {
    if (!is_digit(line[i])) return std::nullopt;
    v = v * 10 + (line[i] - '0');
  }
  if (line[1] == '-' && v == 0) return std::nullopt;  // one spelling of zero: +0...0
  return Report{static_cast<Axis>(line[0] - 'X'), line[1] == '-' ? -v : v};
}

std::size_t format_error(std::uint8_t code, std::span<std::uint8_t, kErrorLength> out) {
  if (code == 0 || code > 99) return 0;
  out[0] = 'E';
  out[1] = static_cast<std::uint8_t>('0' + code / 10U);
  out[2] = static_cast<std::uint8_t>('0' + code % 10U);
  out[3] = kEnd;
  return kErrorLength;
}

std::optional<std::uint8_t> parse_error(std::span<const std::uint8_t> line) {
  if (line.size() != kErrorLength || line[0] != 'E' || line[3] != kEnd) return std::nullopt;
  if (!is_digit(line[1]) || !is_digit(line[2])) return std::nullopt;
  const auto code = static_cast<std::uint8_t>((line[1] - '0') * 10 + (line[2] - '0'));
  if (code == 0) return std::nullopt;
  return code;
}

std::optional<Framer::Event> Framer::push(std::uint8_t b) {
  const std::uint32_t at = offset_++;
  if (dropping_) {
    if (b == kEnd) dropping_ = false;
    return std::nullopt;
  }
  if (len_ == 0 && (b == '\r' || b == '\n' || b == ' ' || b == '\t')) return std::nullopt;
  if (len_ == 0) start_ = at;
  if (len_ == kMaxLine) {
    // A byte past the longest command: the line is lost, and so is the rest of it up to the
    // next `;` (unless this byte is that `;`).
    len_ = 0;
    dropping_ = b != kEnd;
    ++counters_.rejected;
    return Event{{}, {Error::TooLong, static_cast<std::uint8_t>(kMaxLine)}, start_};
  }
  buf_[len_++] = b;
  if (b != kEnd) return std::nullopt;
  Event e;
  e.stream_offset = start_;
  e.rejection = parse(std::span<const std::uint8_t>(buf_.data(), len_), e.command);
  len_ = 0;
  ++(e.rejection.ok() ? counters_.accepted : counters_.rejected);
  return e;
}

}  // namespace ap::unit3_wire
