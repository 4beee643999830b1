// The fault injector of the simulated link (docs/sim.md "Fault injection"). Its own object so
// that the PC side (pc.cpp, the largest object of the simulator) does not recompile when the
// injector changes.
#include "sim/xy/fault_link.hpp"

#include <algorithm>
#include <utility>

namespace ap::sim::xy {

FaultLink::FaultLink(const std::vector<scenario::Fault>& faults, scenario::Direction dir, std::uint64_t seed,
                     LinkObserver* observer)
    : observer_(observer), rng_(seed) {
  for (const scenario::Fault& f : faults) {
    if (f.dir == scenario::Direction::both || f.dir == dir) faults_.push_back(f);
  }
}

void FaultLink::push(std::int64_t t, Bytes frame, LinkStats& st) {
  ++st.frames;
  FrameTag tag{entered_++, 0, false, false};
  if (cut(t)) {
    ++st.cut;
    return;
  }
  std::int64_t at = t;
  bool dup = false;
  bool reorder = false;
  for (const scenario::Fault& f : faults_) {
    if (t < f.from_us || (f.to_us && t >= *f.to_us)) continue;
    const double p = f.amount.value / 100.0;
    switch (f.kind) {
      case scenario::FaultKind::drop:
        if (roll(p)) {
          ++st.dropped;
          return;
        }
        break;
      case scenario::FaultKind::corrupt:
        if (roll(p) && !frame.empty()) {
          std::uniform_int_distribution<std::size_t> pos(0, frame.size() - 1);
          std::uniform_int_distribution<int> mask(1, 255);
          frame[pos(rng_)] ^= static_cast<std::uint8_t>(mask(rng_));
          ++st.corrupted;
          ++tag.corruptions;
        }
        break;
      case scenario::FaultKind::duplicate:
        if (roll(p)) dup = true;
        break;
      case scenario::FaultKind::reorder:
        if (roll(p)) reorder = true;
        break;
      case scenario::FaultKind::delay: {
        std::int64_t d = static_cast<std::int64_t>(f.amount.value);
        if (f.jitter) {
          std::uniform_int_distribution<std::int64_t> j(0, static_cast<std::int64_t>(f.jitter->value));
          d += j(rng_);
        }
        at += d;
        ++st.delayed;
        break;
      }
    }
  }
  if (reorder && !held_) {
    tag.reordered = true;
    held_ = Held{at, std::move(frame), tag};
    ++st.reordered;
    return;
  }
  queue_.push_back({at, frame, tag});
  if (dup) {
    FrameTag copy = tag;
    copy.duplicate = true;
    queue_.push_back({at, frame, copy});
    ++st.duplicated;
  }
  if (held_) {   // the held frame goes out right after the one that overtook it
    held_->at = std::max(at, held_->at);
    queue_.push_back(std::move(*held_));
    held_.reset();
  }
}

Bytes FaultLink::pop(std::int64_t t, std::size_t max_bytes, LinkStats& st) {
  Bytes out;
  std::vector<FrameTag> tags;
  std::stable_sort(queue_.begin(), queue_.end(), [](const Held& a, const Held& b) { return a.at < b.at; });
  while (!queue_.empty() && queue_.front().at <= t && out.size() + queue_.front().bytes.size() <= max_bytes) {
    if (cut(t)) {
      ++st.cut;
    } else {
      out.insert(out.end(), queue_.front().bytes.begin(), queue_.front().bytes.end());
      tags.push_back(queue_.front().tag);
      ++st.delivered;
    }
    queue_.pop_front();
  }
  if (observer_ != nullptr) observer_->left(t, out, tags);
  return out;
}

bool FaultLink::roll(double p) { return p > 0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p; }

}  // namespace ap::sim::xy
