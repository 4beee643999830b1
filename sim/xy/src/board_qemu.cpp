// The simulated board's QEMU target (sim/xy/board.hpp, docs/qemu.md "Co-simulation"): the image
// runs the board, the device models answer its transactions, and the host core mirrors it.
// This file is the image's side: its session (start, one granted tick, the end of the run
// with its stack report) and the answers to its SPI, ADC, I2C and pin messages. The host
// core's side, compared with what the image did, is board_mirror.cpp.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

#include "sim/xy/board.hpp"

namespace ap::sim::xy {
namespace {

// RLS Orbis programming as the encoder sees it: the unlock bytes, then the command that sets
// the reading of where the shaft stands now ('Z', the position/multi-turn preset) with a 32-bit
// count, MSB first, in one chip-select frame (docs/motion.md "Homing and the encoder zero").
constexpr std::array<std::uint8_t, 4> kOrbisUnlock{0xCD, 0xEF, 0x89, 0xAB};
constexpr std::uint8_t kOrbisSetPosition = 0x5A;
constexpr std::size_t kOrbisProgramLength = 9;

using xy_cosim::Kind;
using Clock = std::chrono::steady_clock;

// The board port's scaling (docs/qemu.md "Inputs"), inverted: the code whose conversion gives
// back exactly this value. Battery: mV = code * 6600 / 65536 rounded down, so the smallest code
// with code * 6600 >= mV * 65536; charge current: code = 32768 + 8 mA.
std::uint16_t battery_code(std::uint16_t mv) {
  const std::uint64_t code = (std::uint64_t{mv} * 65536U + 6599U) / 6600U;
  return static_cast<std::uint16_t>(std::min<std::uint64_t>(code, 65535U));
}
std::uint16_t charge_code(std::int32_t ma) {
  return static_cast<std::uint16_t>(std::clamp<std::int64_t>(32768 + std::int64_t{8} * ma, 0, 65535));
}

std::string hex(std::uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%08x", v);
  return b;
}

}  // namespace

void SimBoard::qemu_start() {
  qemu_stop();
  QemuOptions o;
  o.elf = opt_.qemu_image;
  if (!opt_.qemu_dir.empty()) {
    o.work_dir = opt_.qemu_dir;
  } else if (!opt_.out_dir.empty()) {
    o.work_dir = opt_.out_dir + "/qemu";
  } else {
    o.work_dir = (std::filesystem::temp_directory_path() /
                  ("axisproof-qemu-" + std::to_string(::getpid()) + "-" + std::to_string(opt_.id))).string();
  }
  const auto t0 = Clock::now();
  qemu_log_.clear();
  qemu_log_pos_ = 0;
  image_tx_.clear();
  image_tx_pos_ = 0;
  image_motor_ = {};
  image_encoder_zero_ = {};
  image_kill_ = false;
  image_charger_ = true;
  image_olat_b_ = 0xC0;
  image_iodir_b_ = 0xFF;
  link_delivered_ = 0;
  image_ticks_ = 0;
  image_ready_ = false;
  ++qemu_stats_.boots;
  try {
    qemu_ = std::make_unique<QemuImage>(o);
    const QemuImage::Message hello = qemu_->next();
    if (hello.kind != Kind::Hello || hello.payload.size() != 1 || hello.payload[0] != xy_cosim::kVersion) {
      throw std::runtime_error("the image did not say hello (protocol version " + std::to_string(xy_cosim::kVersion) + ")");
    }
    // Its boot: FRAM load, driver set-up, the first inputs; done when it waits for tick 1.
    qemu_serve(Kind::Ready, nullptr);
    image_ready_ = true;
  } catch (const std::exception& e) {
    qemu_fail(std::string("boot: ") + e.what());
    qemu_.reset();
  }
  qemu_stats_.wall_s += std::chrono::duration<double>(Clock::now() - t0).count();
}

void SimBoard::qemu_stop() {
  if (!qemu_) return;
  try {
    if (!image_ready_) qemu_serve(Kind::Ready, nullptr);
    qemu_->end();
    QemuImage::Message r;
    qemu_serve(Kind::Report, &r);
    if (r.payload.size() != 12) throw std::runtime_error("a short report");
    const std::uint32_t used = xy_cosim::get_u32(r.payload.data());
    const std::uint32_t size = xy_cosim::get_u32(r.payload.data() + 4);
    qemu_stats_.stack_used = std::max(qemu_stats_.stack_used, used);
    qemu_stats_.stack_size = size;
    if (used >= size) qemu_fail("the stack was used to its end (" + std::to_string(size) + " bytes)");
  } catch (const std::exception& e) {
    qemu_fail(std::string("end of run: ") + e.what());
  }
  qemu_.reset();
}

void SimBoard::qemu_serve(Kind until, QemuImage::Message* last) {
  for (;;) {
    QemuImage::Message m = qemu_->next();
    if (m.kind == until) {
      if (last != nullptr) *last = std::move(m);
      return;
    }
    qemu_answer(m);
  }
}

void SimBoard::qemu_answer(const QemuImage::Message& m) {
  const std::vector<std::uint8_t>& p = m.payload;
  auto need = [&](bool ok, const char* what) {
    if (!ok) throw std::runtime_error(std::string("a malformed ") + what + " message");
  };
  switch (m.kind) {
    case Kind::Spi: {
      need(p.size() >= 2, "SPI");
      const std::uint8_t dev = p[0];
      const std::span<const std::uint8_t> mosi(p.data() + 1, p.size() - 1);
      std::vector<std::uint8_t> miso(mosi.size(), 0);
      xy_board::Inputs now;
      fill_inputs(now);
      switch (static_cast<xy_cosim::SpiDevice>(dev)) {
        case xy_cosim::SpiDevice::TmcX:
        case xy_cosim::SpiDevice::TmcY: {
          need(mosi.size() == 5, "TMC2130 datagram");
          xy_tmc2130::Datagram tx{}, rx{};
          std::copy(mosi.begin(), mosi.end(), tx.begin());
          (void)tmc_device(dev, tx, rx);
          std::copy(rx.begin(), rx.end(), miso.begin());
          qemu_log_.push_back({dev, {mosi.begin(), mosi.end()}, miso});
          break;
        }
        case xy_cosim::SpiDevice::Fram:
          (void)fram_device(mosi, miso);
          qemu_log_.push_back({dev, {mosi.begin(), mosi.end()}, miso});
          break;
        case xy_cosim::SpiDevice::EncoderX:
        case xy_cosim::SpiDevice::EncoderY: {
          if (mosi.size() == kOrbisProgramLength && std::equal(kOrbisUnlock.begin(), kOrbisUnlock.end(), mosi.begin()) &&
              mosi[4] == kOrbisSetPosition) {
            // The zero programming of a completed homing (docs/motion.md); the host core's
            // encoder_zero applies it after comparing.
            std::int64_t c = 0;
            for (std::size_t k = 5; k < 9; ++k) c = c << 8 | mosi[k];
            image_encoder_zero_[dev == 3 ? 0 : 1] = static_cast<std::int32_t>(static_cast<std::uint32_t>(c));
            miso.assign(mosi.size(), 0);
            break;
          }
          need(mosi.size() == 4, "encoder");
          const xy_axis::EncoderReading& e = now.encoder[dev == 3 ? 0 : 1];
          const auto turns = static_cast<std::uint16_t>(e.turns);
          const auto low = static_cast<std::uint16_t>(static_cast<unsigned>(e.counts) << 2U | (e.valid != 0 ? 3U : 0U));
          miso = {static_cast<std::uint8_t>(turns >> 8), static_cast<std::uint8_t>(turns),
                  static_cast<std::uint8_t>(low >> 8), static_cast<std::uint8_t>(low)};
          break;
        }
        case xy_cosim::SpiDevice::Expander:
          if (mosi.size() == 4 && mosi[0] == 0x41 && mosi[1] == 0x12) {
            const std::uint16_t w = expander_word(now);
            miso[2] = static_cast<std::uint8_t>(w & 0xFFU);
            miso[3] = static_cast<std::uint8_t>(w >> 8);
          } else if (mosi.size() == 3 && mosi[0] == 0x40 && mosi[1] == 0x15) {
            image_olat_b_ = mosi[2];
          } else if (mosi.size() == 3 && mosi[0] == 0x40 && mosi[1] == 0x01) {
            image_iodir_b_ = mosi[2];
          } else {
            qemu_fail("an expander transaction the board does not make");
          }
          break;
        default: throw std::runtime_error("SPI to device " + std::to_string(dev));
      }
      qemu_->reply(miso);
      return;
    }
    case Kind::Adc: {
      need(p.size() == 1, "ADC");
      xy_board::Inputs now;
      fill_inputs(now);
      const std::uint16_t code = p[0] == 0 ? battery_code(now.battery_mv) : charge_code(now.charge_ma);
      std::uint8_t r[2];
      xy_cosim::put_u16(r, code);
      qemu_->reply(r);
      return;
    }
    case Kind::I2c: {
      need(p.size() >= 2 && p[0] <= 0x7F, "I2C");
      const std::span<const std::uint8_t> wr(p.data() + 2, p.size() - 2);
      std::vector<std::uint8_t> rd(p[1], 0);
      const xy_i2c::Status st = i2c_device(p[0], wr, rd);
      qemu_log_.push_back({static_cast<std::uint8_t>(kI2cLogKey | p[0]), {wr.begin(), wr.end()}, rd, static_cast<std::uint8_t>(st)});
      std::vector<std::uint8_t> r;
      r.reserve(rd.size() + 1);
      r.push_back(static_cast<std::uint8_t>(st));
      r.insert(r.end(), rd.begin(), rd.end());
      qemu_->reply(r);
      return;
    }
    case Kind::PinWrite:
      need(p.size() == 2 && (p[0] <= 1 || p[0] == static_cast<std::uint8_t>(xy_cosim::Pin::KillSwitch) ||
                             p[0] == static_cast<std::uint8_t>(xy_cosim::Pin::ChargerEnable)),
           "pin");
      if (p[0] == static_cast<std::uint8_t>(xy_cosim::Pin::KillSwitch)) {
        image_kill_ = p[1] != 0;
      } else if (p[0] == static_cast<std::uint8_t>(xy_cosim::Pin::ChargerEnable)) {
        image_charger_ = p[1] != 0;
      } else {
        image_motor_[p[0]].dir = p[1] != 0;
      }
      return;
    case Kind::Step: {
      need(p.size() == 9 && p[0] <= 1, "step timer");
      ImageMotor& im = image_motor_[p[0]];
      im.armed = true;
      im.psc = xy_cosim::get_u16(p.data() + 1);
      im.arr = xy_cosim::get_u16(p.data() + 3);
      im.steps = static_cast<std::int32_t>(xy_cosim::get_u32(p.data() + 5));
      return;
    }
    case Kind::Fault: {
      need(p.size() == 17, "fault");
      const std::uint8_t exc = p[0];
      const std::uint32_t pc = xy_cosim::get_u32(p.data() + 1);
      const std::string regs = "(lr " + hex(xy_cosim::get_u32(p.data() + 5)) + ", CFSR " + hex(xy_cosim::get_u32(p.data() + 9)) +
                               ", HFSR " + hex(xy_cosim::get_u32(p.data() + 13)) + ")";
      namespace stop = xy_cosim::stop;
      std::string what;
      switch (exc) {
        case stop::kStackRanOut: what = "stack overflow at sp " + hex(pc) + ": no room to stack the fault's frame " + regs; break;
        case stop::kStackPaint: what = "stack overflow (the thread stack's last painted word was overwritten)"; break;
        case stop::kHandlerStackPaint: what = "stack overflow (the exception stack's last painted word was overwritten)"; break;
        case stop::kChannel: what = "the co-simulation channel broke"; break;
        default: what = "exception " + std::to_string(exc) + " at pc " + hex(pc) + " " + regs; break;
      }
      throw std::runtime_error("the image faulted: " + what);
    }
    case Kind::Hello: throw std::runtime_error("the image restarted (a reset: watchdog, fault or lock-up)");
    default: throw std::runtime_error("an unexpected message '" + std::string(1, static_cast<char>(m.kind)) + "'");
  }
}

void SimBoard::qemu_tick() {
  const auto t0 = Clock::now();
  qemu_log_.clear();
  qemu_log_pos_ = 0;
  image_tx_.clear();
  image_tx_pos_ = 0;
  for (ImageMotor& im : image_motor_) im.armed = false;
  try {
    if (!image_ready_) qemu_serve(Kind::Ready, nullptr);
    image_ready_ = false;
    qemu_->grant(image_ticks_ + 1, link_delivered_);
    QemuImage::Message done;
    qemu_serve(Kind::Done, &done);
    if (done.payload.size() != 14) throw std::runtime_error("a short Done");
    const std::uint32_t tick = xy_cosim::get_u32(done.payload.data());
    if (tick != image_ticks_ + 1) throw std::runtime_error("tick " + std::to_string(tick) + " done, " + std::to_string(image_ticks_ + 1) + " granted");
    image_ticks_ = tick;
    image_tx_ = qemu_->link_read(xy_cosim::get_u16(done.payload.data() + 4));
    image_pos_[0] = static_cast<std::int32_t>(xy_cosim::get_u32(done.payload.data() + 6));
    image_pos_[1] = static_cast<std::int32_t>(xy_cosim::get_u32(done.payload.data() + 10));
    ++qemu_stats_.ticks;
  } catch (const std::exception& e) {
    qemu_fail(std::string("tick ") + std::to_string(image_ticks_ + 1) + ": " + e.what());
    qemu_.reset();
  }
  qemu_stats_.wall_s += std::chrono::duration<double>(Clock::now() - t0).count();
}

void SimBoard::write_qemu_stats() const {
  const QemuStats& q = qemu_stats_;
  std::ofstream o(opt_.out_dir + "/qemu.txt", std::ios::trunc);
  const double emulated = static_cast<double>(q.ticks) / 1000.0;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "ticks %llu\nemulated_s %.3f\nwall_s %.3f\nratio %.2f\nboots %llu\nstack_used %u\nstack_size %u\n"
                "divergences %llu\n",
                static_cast<unsigned long long>(q.ticks), emulated, q.wall_s, q.wall_s > 0 ? emulated / q.wall_s : 0.0,
                static_cast<unsigned long long>(q.boots), q.stack_used, q.stack_size,
                static_cast<unsigned long long>(q.divergences));
  o << buf;
}

}  // namespace ap::sim::xy
