// The QEMU image of the XY board as the simulated board's target (docs/qemu.md): starts
// qemu-system-arm on the image, and carries its two channels: the board's link UART (USART1,
// a socket chardev) and the co-simulation channel (two FIFOs the image opens by semihosting,
// protocol/xy/cosim/wire.hpp). Everything here blocks; a silent image is an error after a wall
// timeout, never a hang.
#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/xy/cosim/wire.hpp"

namespace ap::sim::xy {

struct QemuOptions {
  std::string elf;                 // the image (build/m4/firmware/xy/ap_xy_qemu.elf)
  std::string work_dir;            // FIFOs, socket and qemu.log go here
  std::string qemu = "qemu-system-arm";
  // Instruction counting: one instruction = 2^shift ns of virtual time; idle time (waiting for
  // SysTick) is skipped. shift 4 is 62.5 M instructions per virtual second, a little below the
  // STM32L476's 80 MHz.
  int icount_shift = 4;
  std::chrono::milliseconds timeout{20'000};
};

class QemuImage {
 public:
  struct Message {
    xy_cosim::Kind kind{};
    std::vector<std::uint8_t> payload;
  };

  explicit QemuImage(QemuOptions opt);
  ~QemuImage();
  QemuImage(const QemuImage&) = delete;
  QemuImage& operator=(const QemuImage&) = delete;

  // The next message from the image.
  Message next();
  void reply(std::span<const std::uint8_t> bytes);
  void grant(std::uint32_t tick, std::uint32_t link_delivered);
  void end();
  // The board's link: bytes to its RX pin, bytes from its TX pin.
  void link_write(std::span<const std::uint8_t> bytes);
  std::vector<std::uint8_t> link_read(std::size_t n);
  // The tail of QEMU's own output (for error messages).
  std::string log_tail() const;

 private:
  void send(xy_cosim::Kind kind, std::span<const std::uint8_t> payload);
  // Waits for `fd` to have bytes; a silent image is an error after the timeout.
  void wait_readable(int fd, const char* what);
  // At least one and at most n bytes.
  std::size_t read_some(int fd, std::uint8_t* buf, std::size_t n, const char* what);
  void read_exact(int fd, std::uint8_t* buf, std::size_t n, const char* what);

  QemuOptions opt_;
  int pid_ = -1;
  int to_host_ = -1;
  int to_image_ = -1;
  int listen_ = -1;
  int link_ = -1;
  std::vector<std::uint8_t> in_;   // read-ahead of the to-host FIFO
  std::size_t in_pos_ = 0;
};

}  // namespace ap::sim::xy
