// DomainLease: see pc/dds/domain.hpp.
#include "pc/dds/domain.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

#include "pc/dds/bus.hpp"

namespace ap::dds {

DomainLease DomainLease::claim(std::uint32_t first, std::uint32_t last) {
  if (last > kMaxDomainId || first > last) {
    throw Error("dds: bad domain range " + std::to_string(first) + ".." + std::to_string(last));
  }
  for (std::uint32_t id = first; id <= last; ++id) {
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      throw Error("dds: socket() failed for the domain lease");
    }
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(kLockPortBase + id));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    sockaddr* sa = reinterpret_cast<sockaddr*>(&a);
    if (bind(fd, sa, sizeof a) == 0 && listen(fd, 1) == 0) {
      return DomainLease(id, fd);
    }
    close(fd);
  }
  throw Error("dds: no free domain id in " + std::to_string(first) + ".." + std::to_string(last));
}

DomainLease::DomainLease(DomainLease&& other) noexcept : id_(other.id_), fd_(other.fd_) { other.fd_ = -1; }

DomainLease::~DomainLease() {
  if (fd_ >= 0) {
    close(fd_);
  }
}

std::uint32_t fixed_or_claimed(std::optional<std::uint32_t> fixed, std::optional<DomainLease>& lease) {
  if (fixed) return *fixed;
  lease.emplace(DomainLease::claim(1, kMaxDomainId));
  return lease->id();
}

}  // namespace ap::dds
