// The QEMU image as a process (sim/xy/qemu_image.hpp, docs/qemu.md "Co-simulation").
#include "sim/xy/qemu_image.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace ap::sim::xy {
namespace {

std::runtime_error sys_error(const std::string& what) { return std::runtime_error(what + ": " + std::strerror(errno)); }

void make_fifo(const std::string& path) {
  std::filesystem::remove(path);
  if (::mkfifo(path.c_str(), 0600) != 0) throw sys_error("mkfifo " + path);
}

}  // namespace

QemuImage::QemuImage(QemuOptions opt) : opt_(std::move(opt)) {
  namespace fs = std::filesystem;
  if (!fs::exists(opt_.elf)) throw std::runtime_error("no QEMU image at " + opt_.elf + " (ci/m4-build builds it)");
  fs::create_directories(opt_.work_dir);
  const std::string dir = fs::absolute(opt_.work_dir).string();
  make_fifo(dir + "/cosim.to-host");
  make_fifo(dir + "/cosim.to-image");
  // Both ends read-write: neither open blocks, and a read waits for data instead of seeing end of
  // file before the image has opened its end.
  to_host_ = ::open((dir + "/cosim.to-host").c_str(), O_RDWR | O_CLOEXEC);
  to_image_ = ::open((dir + "/cosim.to-image").c_str(), O_RDWR | O_CLOEXEC);
  if (to_host_ < 0 || to_image_ < 0) throw sys_error("open the co-simulation FIFOs");
  const std::string sock = dir + "/link.sock";
  fs::remove(sock);
  listen_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (sock.size() >= sizeof addr.sun_path) throw std::runtime_error("socket path too long: " + sock);
  std::memcpy(addr.sun_path, sock.c_str(), sock.size() + 1);
  if (listen_ < 0 || ::bind(listen_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || ::listen(listen_, 1) != 0) {
    throw sys_error("link socket " + sock);
  }
  const std::string elf = fs::absolute(opt_.elf).string();
  std::vector<std::string> args = {opt_.qemu, "-M", "netduinoplus2", "-display", "none", "-monitor", "none",
                                   "-kernel", elf, "-semihosting-config", "enable=on,target=native",
                                   "-icount", "shift=" + std::to_string(opt_.icount_shift) + ",sleep=off",
                                   "-chardev", "socket,id=link,path=" + sock, "-serial", "chardev:link"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // fork + exec rather than posix_spawn, for PR_SET_PDEATHSIG: QEMU gets SIGKILL when the thread
  // that started it ends, which this object (owned by the board, on that thread) never outlives.
  // The destructor cannot kill QEMU if this process dies without unwinding (SIGKILL, a sanitizer's
  // abort), and the image cannot always stop itself: before it has opened its FIFOs, QEMU waits
  // in open() for a host that is gone (docs/qemu.md, "When the host dies"). Between fork and exec
  // only async-signal-safe calls: everything they need is built above.
  const std::string log_path = dir + "/qemu.log";
  const pid_t parent = ::getpid();
  int exec_err[2];  // close-on-exec: end of file means exec succeeded, an errno means it failed
  if (::pipe2(exec_err, O_CLOEXEC) != 0) throw sys_error("pipe");
  const pid_t pid = ::fork();
  if (pid < 0) throw sys_error("fork for " + opt_.qemu);
  if (pid == 0) {
    int err = 0;
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) ::_exit(127);
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in >= 0 && out >= 0 && ::dup2(in, 0) >= 0 && ::dup2(out, 1) >= 0 && ::dup2(out, 2) >= 0 && ::chdir(dir.c_str()) == 0) {
      ::execvp(opt_.qemu.c_str(), argv.data());
    }
    err = errno;
    (void)!::write(exec_err[1], &err, sizeof err);
    ::_exit(127);
  }
  ::close(exec_err[1]);
  int err = 0;
  const ssize_t got = ::read(exec_err[0], &err, sizeof err);
  ::close(exec_err[0]);
  if (got > 0) {
    ::waitpid(pid, nullptr, 0);
    errno = err;
    throw sys_error("start " + opt_.qemu + " (the bootstrap installs qemu-system-arm)");
  }
  pid_ = pid;
  pollfd p{listen_, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(opt_.timeout.count())) != 1) {
    throw std::runtime_error("QEMU did not connect the link socket; " + log_tail());
  }
  link_ = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC);
  if (link_ < 0) throw sys_error("accept the link socket");
}

QemuImage::~QemuImage() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  for (int fd : {to_host_, to_image_, listen_, link_}) {
    if (fd >= 0) ::close(fd);
  }
}

std::string QemuImage::log_tail() const {
  std::ifstream in(opt_.work_dir + "/qemu.log");
  std::stringstream s;
  s << in.rdbuf();
  std::string t = s.str();
  // QEMU's own verdict ("qemu: fatal: Lockup: ...") comes first, before a register dump that
  // would push it out of the tail.
  if (const auto f = t.find("qemu: fatal:"); f != std::string::npos) t = t.substr(f, t.find('\n', f) - f);
  if (t.size() > 400) t = t.substr(t.size() - 400);
  return t.empty() ? std::string("QEMU printed nothing") : "QEMU said: " + t;
}

void QemuImage::wait_readable(int fd, const char* what) {
  // In slices, so that a QEMU that exits (its own "fatal: Lockup", a crash) is reported at once
  // rather than after the whole timeout: the FIFOs are open read-write here, so its exit does
  // not end them.
  constexpr int kSliceMs = 200;
  for (long waited = 0;;) {
    pollfd p{fd, POLLIN, 0};
    const int r = ::poll(&p, 1, kSliceMs);
    if (r > 0) return;
    if (r < 0) {
      if (errno == EINTR) continue;
      throw sys_error(what);
    }
    waited += kSliceMs;
    int status = 0;
    if (pid_ > 0 && ::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      throw std::runtime_error(std::string("QEMU exited while the host waited for ") + what + "; " + log_tail());
    }
    if (waited >= opt_.timeout.count()) {
      throw std::runtime_error(std::string("the image went silent (") + what + ", " + std::to_string(opt_.timeout.count()) + " ms)");
    }
  }
}

std::size_t QemuImage::read_some(int fd, std::uint8_t* buf, std::size_t n, const char* what) {
  for (;;) {
    wait_readable(fd, what);
    const ssize_t got = ::read(fd, buf, n);
    if (got > 0) return static_cast<std::size_t>(got);
    if (got < 0 && errno == EINTR) continue;
    throw std::runtime_error(std::string(what) + ": closed; " + log_tail());
  }
}

void QemuImage::read_exact(int fd, std::uint8_t* buf, std::size_t n, const char* what) {
  for (std::size_t done = 0; done < n;) done += read_some(fd, buf + done, n - done, what);
}

QemuImage::Message QemuImage::next() {
  auto byte = [&]() {
    if (in_pos_ == in_.size()) {
      in_.resize(4096);
      in_pos_ = 0;
      try {
        in_.resize(read_some(to_host_, in_.data(), in_.size(), "the co-simulation channel"));
      } catch (...) {
        in_.clear();
        throw;
      }
    }
    return in_[in_pos_++];
  };
  Message m;
  m.kind = static_cast<xy_cosim::Kind>(byte());
  const std::size_t n = byte();
  m.payload.resize(n);
  for (std::size_t i = 0; i < n; ++i) m.payload[i] = byte();
  return m;
}

void QemuImage::send(xy_cosim::Kind kind, std::span<const std::uint8_t> payload) {
  if (payload.size() > xy_cosim::kMaxPayload) throw std::logic_error("co-simulation payload too long");
  std::vector<std::uint8_t> m;
  m.reserve(payload.size() + 2);
  m.push_back(static_cast<std::uint8_t>(kind));
  m.push_back(static_cast<std::uint8_t>(payload.size()));
  m.insert(m.end(), payload.begin(), payload.end());
  std::size_t done = 0;
  while (done < m.size()) {
    const ssize_t w = ::write(to_image_, m.data() + done, m.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw sys_error("write the co-simulation channel");
    done += static_cast<std::size_t>(w);
  }
}

void QemuImage::reply(std::span<const std::uint8_t> bytes) { send(xy_cosim::Kind::Reply, bytes); }

void QemuImage::grant(std::uint32_t tick, std::uint32_t link_delivered) {
  std::uint8_t p[8];
  xy_cosim::put_u32(p, tick);
  xy_cosim::put_u32(p + 4, link_delivered);
  send(xy_cosim::Kind::Grant, p);
}

void QemuImage::end() { send(xy_cosim::Kind::End, {}); }

void QemuImage::link_write(std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::send(link_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw sys_error("write the link socket");
    done += static_cast<std::size_t>(w);
  }
}

std::vector<std::uint8_t> QemuImage::link_read(std::size_t n) {
  std::vector<std::uint8_t> out(n);
  if (n > 0) read_exact(link_, out.data(), n, "the link's TX bytes");
  return out;
}

}  // namespace ap::sim::xy
