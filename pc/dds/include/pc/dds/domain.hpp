// DomainLease: a DDS domain id held for the life of the object, so tests that run in parallel
// under ctest (each its own process) never share a domain (distinct ids have disjoint port
// ranges: 7400 + 250 * id). The lock is a TCP listen socket on 127.0.0.1:(kLockPortBase + id),
// the scheme of ROS 2's domain_coordinator; the kernel releases it when the process dies.
#pragma once

#include <cstdint>
#include <optional>

namespace ap::dds {

inline constexpr std::uint16_t kLockPortBase = 32768;
inline constexpr std::uint32_t kMaxDomainId = 232;   // 7400 + 250 * id + offsets < 65536

class DomainLease {
 public:
  // First free id in [first, last]; throws ap::dds::Error when all are taken.
  static DomainLease claim(std::uint32_t first, std::uint32_t last);
  DomainLease(DomainLease&& other) noexcept;
  DomainLease& operator=(DomainLease&&) = delete;
  DomainLease(const DomainLease&) = delete;
  DomainLease& operator=(const DomainLease&) = delete;
  ~DomainLease();
  [[nodiscard]] std::uint32_t id() const { return id_; }

 private:
  DomainLease(std::uint32_t id, int fd) : id_(id), fd_(fd) {}
  std::uint32_t id_;
  int fd_;
};

// The domain a run uses: `fixed` when given, else a free one claimed into `lease`, which holds
// it for as long as the caller keeps `lease`.
std::uint32_t fixed_or_claimed(std::optional<std::uint32_t> fixed, std::optional<DomainLease>& lease);

}  // namespace ap::dds
