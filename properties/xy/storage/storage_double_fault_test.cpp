// Exhaustive double faults over two consecutive saves (docs/storage.md, "Save protocol" and
// "Double faults"). S1 is a PARAM_SET (low_battery 3300 -> 3400), S2 the record_shutdown that
// follows it; the step counters S2 writes lie after low_battery in the record, so S2's record
// agrees with S1's on its first 0x3C bytes: the shape in which a torn S2 write could rebuild
// S1's record from S2's prefix and S1's tail (the store_ops finding).
//
// Oracle (the protocol's promise, not the code's): every boot loads the set the previous boot
// or the last Ok save established ("committed"), or, after a power cut, the set whose save the
// cut interrupted. So a set whose save was reported failed never loads once a boot or an Ok
// save has passed it by, and a mixture of two sets never loads.
//
// Faults: a power cut after any SPI byte of S1 or S2 (the model's cut: every completed byte
// stays, the chip is dead until power_on, the store runs on against it); a single bit flip
// on the write or read path of one cell of the target copy, either on exactly one of the
// cell's writes/reads in that save or on every one of them (a weak cell). The flips sit on
// the bus between the store and the model, so the chip stores (or the store reads) the
// flipped byte.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/xy/storage/fram_map.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/record.hpp"
#include "core/xy/storage/store.hpp"
#include "models/xy/fram/mb85rs256b.hpp"

namespace {

using namespace ap::xy_storage;
using ap::model::Mb85rs256b;

// Only the two records are ever written; everything else stays zero.
constexpr std::size_t kImage = 0x200;
constexpr std::int64_t kS1LowBattery = 3400;
constexpr std::int32_t kS2CountX = 123456;
constexpr std::int32_t kS2CountY = -42;

enum class Path : std::uint8_t { Write, Read };

// One bit flip on one cell of the copy the save writes (a save reads and writes no other
// cell): on the cell's `nth` write (resp. read) during the save, or on all of them when nth == 0.
struct Flip {
  Path path;
  std::uint8_t offset;  // in the record
  std::uint8_t mask;
  std::uint32_t nth;
};

// The record offset of a chip address, or kRecordSize outside both copies.
std::size_t offset_of(std::size_t address) {
  for (const std::uint16_t base : kCopyBase) {
    if (address >= base && address < base + kRecordSize) return address - base;
  }
  return kRecordSize;
}

// One SPI frame of a recorded save: the chip's state when it started and the bytes sent.
struct Frame {
  std::array<std::uint8_t, kImage> before;
  std::uint8_t status;
  std::vector<std::uint8_t> tx;
};

// The bus between the store and the model; applies the armed flip.
struct FlipBus {
  Mb85rs256b* chip = nullptr;
  std::optional<Flip> flip;
  std::uint32_t seen = 0;  // writes (resp. reads) of the flip's cell so far
  std::uint32_t hits = 0;  // flips applied
  std::string* mosi = nullptr;  // when set, every byte sent to the chip (flips included)
  std::vector<Frame>* frames = nullptr;  // when set, every frame with the state it started from

  void note(std::span<const std::uint8_t> sent) {
    if (mosi != nullptr) {
      mosi->append(reinterpret_cast<const char*>(sent.data()), sent.size());
      mosi->push_back('|');
    }
    if (frames != nullptr) {
      Frame f{{}, chip->status(), std::vector<std::uint8_t>(sent.begin(), sent.end())};
      std::memcpy(f.before.data(), chip->memory().data(), kImage);
      frames->push_back(std::move(f));
    }
  }

  bool hit() {
    ++seen;
    if (flip->nth == 0 || flip->nth == seen) {
      ++hits;
      return true;
    }
    return false;
  }

  static bool transfer(void* ctx, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
    auto* self = static_cast<FlipBus*>(ctx);
    if (!(self->flip && self->flip->path == Path::Write && tx.size() > 3 && tx[0] == opcode::kWrite)) self->note(tx);
    if (!self->flip || tx.size() <= 3 || (tx[0] != opcode::kWrite && tx[0] != opcode::kRead)) {
      return self->chip->transfer(tx, rx);
    }
    const auto start = static_cast<std::uint16_t>(tx[1] << 8U | tx[2]);
    const Flip& f = *self->flip;
    if (tx[0] == opcode::kWrite && f.path == Path::Write) {
      std::array<std::uint8_t, 3 + kRecordSize> copy{};
      std::memcpy(copy.data(), tx.data(), tx.size());
      for (std::size_t i = 3; i < tx.size(); ++i) {
        if (offset_of(start + (i - 3)) == f.offset && self->hit()) copy[i] ^= f.mask;
      }
      self->note(std::span<const std::uint8_t>(copy.data(), tx.size()));
      return self->chip->transfer(std::span<const std::uint8_t>(copy.data(), tx.size()), rx);
    }
    const bool ok = self->chip->transfer(tx, rx);
    if (tx[0] == opcode::kRead && f.path == Path::Read) {
      for (std::size_t i = 3; i < tx.size(); ++i) {
        if (offset_of(start + (i - 3)) == f.offset && self->hit()) rx[i] ^= f.mask;
      }
    }
    return ok;
  }
  SpiBus bus() noexcept { return SpiBus{&FlipBus::transfer, this}; }
};

// Faults of one save: at most one flip and at most one cut.
struct SaveFaults {
  std::optional<Flip> flip;
  std::optional<std::size_t> cut;  // power dies after this many SPI bytes of the save
};

// What one save did, for the enumeration.
struct SaveTrace {
  std::size_t bytes = 0;   // SPI bytes clocked while powered
  std::uint32_t cell_accesses = 0;  // writes/reads of the flip's cell (0 without a flip)
  std::uint32_t flips = 0;
  bool cut = false;
  SaveResult result{};
};

// The state between S1 and S2: chip image, the store in RAM, the oracle.
struct Between {
  std::array<std::uint8_t, kImage> image{};
  ParameterStore store{SpiBus{nullptr, nullptr}};
  ParameterSet committed{};
};

struct Failure {
  std::string what;
};

std::string describe(const std::optional<Flip>& f) {
  if (!f) return "no flip";
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s flip 0x%02X at record offset 0x%02X on %s", f->path == Path::Write ? "write" : "read",
                f->mask, f->offset, f->nth == 0 ? "every access" : ("access " + std::to_string(f->nth)).c_str());
  return buf;
}

class Rig {
 public:
  Rig() : chip_(std::make_unique<Mb85rs256b>()) { bus_.chip = chip_.get(); }

  // The sets S1 and S2 write, given the set in use before each.
  static ParameterSet s1_set(ParameterSet s) {
    s.low_battery_mv = static_cast<std::uint16_t>(kS1LowBattery);
    return s;
  }
  static ParameterSet s2_set(ParameterSet s) {
    s.step_count_x = kS2CountX;
    s.step_count_y = kS2CountY;
    s.step_counts_valid = true;
    return s;
  }

  // Boots from `image`: the committed set is what that boot loads.
  Between boot_from(const std::array<std::uint8_t, kImage>& image) {
    load(image);
    Between b;
    b.store = ParameterStore(bus_.bus());
    (void)b.store.boot();
    b.committed = b.store.current();
    b.image = image;
    return b;
  }

  // S1 from `start`; after a cut the power comes back and the store reboots (checked).
  // Returns false (with `fail`) on an oracle violation.
  bool s1(const Between& start, const SaveFaults& faults, Between& out, SaveTrace& trace, Failure& fail) {
    load(start.image);
    ParameterStore store = start.store;
    const ParameterSet intended = s1_set(store.current());
    const SaveResult r = run(faults, trace, [&] {
      return store.set_parameter(static_cast<std::uint8_t>(ParamId::LowBatteryMv), kS1LowBattery);
    });
    out.committed = start.committed;
    if (!settle(store, r, intended, trace, out.committed, fail, "S1")) return false;
    out.store = store;
    save_image(out.image);
    return true;
  }

  // S2 from `mid`, then the final reboot.
  bool s2(const Between& mid, const SaveFaults& faults, SaveTrace& trace, Failure& fail) {
    load(mid.image);
    ParameterStore store = mid.store;
    const ParameterSet intended = s2_set(store.current());
    const SaveResult r = run(faults, trace, [&] { return store.record_shutdown(kS2CountX, kS2CountY); });
    ParameterSet committed = mid.committed;
    // settle() ends with the reboot (after a cut) or a probe boot (without one): the final check.
    return settle(store, r, intended, trace, committed, fail, "S2");
  }

  // Record the bytes sent to the chip during the saves (nullptr: stop).
  void record_mosi(std::string* out) { mosi_ = out; }
  void record_frames(std::vector<Frame>* out) { frames_ = out; }

  // The chip image a power cut after byte k of a recorded save leaves: the model's own cut,
  // armed on a second chip set to the state the frame holding byte k started from. Until the
  // cut, a cut run and the recorded run are the same run (the store and the model are
  // deterministic), and after it the chip is dead: nothing the store still does reaches it.
  void image_after_cut(const std::vector<Frame>& frames, std::size_t k, std::array<std::uint8_t, kImage>& out) {
    std::size_t off = 0;
    for (const Frame& f : frames) {
      if (k < off + f.tx.size()) {
        std::memcpy(scratch_->memory().data(), f.before.data(), kImage);
        scratch_->power_on();
        if ((f.status & status::kWel) != 0) {
          const std::array<std::uint8_t, 1> wren{opcode::kWren};
          std::array<std::uint8_t, 1> rx{};
          scratch_->transfer(wren, rx);
        }
        EXPECT_EQ(scratch_->status(), f.status);
        std::vector<std::uint8_t> rx(f.tx.size());
        scratch_->arm_power_cut_after(k - off);
        scratch_->transfer(f.tx, rx);
        std::memcpy(out.data(), scratch_->memory().data(), kImage);
        return;
      }
      off += f.tx.size();
    }
    ADD_FAILURE() << "cut point " << k << " past the recorded save (" << off << " bytes)";
  }

  // Power on with `image`: the boot must load `committed` or `intended`; `out` is that state.
  bool reboot_check(const std::array<std::uint8_t, kImage>& image, const ParameterSet& committed,
                    const ParameterSet& intended, Between& out, Failure& fail, const char* which) {
    out = boot_from(image);
    if (!(out.committed == committed || out.committed == intended)) {
      fail.what = std::string(which) + " cut: reboot loaded neither the committed set nor the one being written";
      return false;
    }
    return true;
  }

 private:
  void load(const std::array<std::uint8_t, kImage>& image) {
    std::memcpy(chip_->memory().data(), image.data(), kImage);
    chip_->power_on();
  }
  void save_image(std::array<std::uint8_t, kImage>& image) const {
    std::memcpy(image.data(), chip_->memory().data(), kImage);
  }

  template <typename Op>
  SaveResult run(const SaveFaults& faults, SaveTrace& trace, Op op) {
    bus_.flip = faults.flip;
    bus_.seen = 0;
    bus_.hits = 0;
    if (faults.cut) chip_->arm_power_cut_after(*faults.cut);
    const std::size_t before = chip_->bytes_clocked();
    bus_.mosi = mosi_;
    bus_.frames = frames_;
    const SaveResult r = op();
    bus_.mosi = nullptr;
    bus_.frames = nullptr;
    trace.bytes = chip_->bytes_clocked() - before;
    trace.cell_accesses = bus_.seen;
    trace.flips = bus_.hits;
    trace.cut = !chip_->powered();
    trace.result = r;
    bus_.flip.reset();
    if (faults.cut && !trace.cut) chip_->power_on();  // disarm a cut the save did not reach
    return r;
  }

  // Applies the oracle to one save's outcome; after a cut, power comes back and the store
  // reboots, and that boot must load the committed set or the one being written.
  bool settle(ParameterStore& store, const SaveResult& r, const ParameterSet& intended, const SaveTrace& trace,
              ParameterSet& committed, Failure& fail, const char* which) {
    if (trace.cut) {
      chip_->power_on();
      store = ParameterStore(bus_.bus());
      (void)store.boot();
      const ParameterSet& now = store.current();
      if (!(now == committed || now == intended)) {
        fail.what = std::string(which) + " cut: reboot loaded neither the committed set nor the one being written";
        return false;
      }
      committed = now;
      return true;
    }
    if (r.ok()) {
      if (!(store.current() == intended)) {
        fail.what = std::string(which) + ": Ok but another set in use";
        return false;
      }
      committed = intended;
    } else if (r.status != StoreStatus::StorageFault || !(store.current() == committed)) {
      fail.what = std::string(which) + ": failed save changed the set in use or was not a StorageFault";
      return false;
    }
    // A reboot now (a probe on the same chip; boot only reads) loads exactly the committed set:
    // never the set of a save reported failed.
    ParameterStore probe(bus_.bus());
    (void)probe.boot();
    if (!(probe.current() == committed)) {
      fail.what = std::string(which) + ": a reboot after the save would load another set than the committed one";
      return false;
    }
    return true;
  }

  std::unique_ptr<Mb85rs256b> chip_;
  FlipBus bus_{};
  std::string* mosi_ = nullptr;
  std::vector<Frame>* frames_ = nullptr;
  std::unique_ptr<Mb85rs256b> scratch_ = std::make_unique<Mb85rs256b>();
};

// Start images: (1) copy A holds the committed set (sequence 7), copy B an older one
// (sequence 6), so the saves target B; (2) a blank chip: defaults, sequence 0, target A (the
// store_ops finding's start).
std::vector<std::pair<const char*, std::array<std::uint8_t, kImage>>> starts() {
  std::vector<std::pair<const char*, std::array<std::uint8_t, kImage>>> out;
  std::array<std::uint8_t, kImage> history{};
  ParameterSet committed = defaults();
  committed.max_acceleration_um_s2 = 15000;
  committed.run_current_cs = 20;
  ParameterSet older = committed;
  older.max_acceleration_um_s2 = 9000;
  RecordBytes r{};
  encode_record(committed, 7, r);
  std::memcpy(history.data() + kCopyBase[0], r.data(), kRecordSize);
  encode_record(older, 6, r);
  std::memcpy(history.data() + kCopyBase[1], r.data(), kRecordSize);
  out.emplace_back("history (A committed, B older)", history);
  out.emplace_back("blank chip (defaults)", std::array<std::uint8_t, kImage>{});
  return out;
}

// The flips of one save: every cell of the copy it writes x (each single access the cell gets
// in the fault-free save, or every access), on the write and on the read path. One bit per
// (cell, access pattern), rotating through all 8 positions from cell to cell: which bit of a
// byte flips changes the value, never which copy is valid when (docs/storage.md).
std::vector<Flip> all_flips(const std::array<std::uint32_t, kRecordSize>& writes,
                            const std::array<std::uint32_t, kRecordSize>& reads) {
  std::vector<Flip> out;
  for (std::size_t i = 0; i < kRecordSize; ++i) {
    const auto o = static_cast<std::uint8_t>(i);
    for (std::uint32_t n = 0; n <= writes[i]; ++n) {
      out.push_back(Flip{Path::Write, o, static_cast<std::uint8_t>(1U << ((i + n) % 8)), n});
    }
    for (std::uint32_t n = 0; n <= reads[i]; ++n) {
      out.push_back(Flip{Path::Read, o, static_cast<std::uint8_t>(1U << ((i + n + 4) % 8)), n});
    }
  }
  return out;
}

// How often a fault-free save (S1 from `start`, or S2 from `mid`) writes and reads each cell of
// its copy, counted by the flip bus itself (a probe flip with mask 0 on each cell).
void count_accesses(Rig& rig, const Between& start, const Between* mid, std::array<std::uint32_t, kRecordSize>& writes,
                    std::array<std::uint32_t, kRecordSize>& reads) {
  for (std::size_t i = 0; i < kRecordSize; ++i) {
    for (const Path p : {Path::Write, Path::Read}) {
      const SaveFaults f{Flip{p, static_cast<std::uint8_t>(i), 0, 0}, std::nullopt};
      SaveTrace t{};
      Failure fail{};
      Between out;
      const bool ok = mid != nullptr ? rig.s2(*mid, f, t, fail) : rig.s1(start, f, out, t, fail);
      EXPECT_TRUE(ok) << fail.what;
      (p == Path::Write ? writes : reads)[i] = t.cell_accesses;
    }
  }
}

std::string image_key(const Between& b) {
  std::string k(reinterpret_cast<const char*>(b.image.data()), kImage);
  // the store's RAM state matters too when S2 runs without a reboot
  k.push_back(static_cast<char>(b.store.sequence() & 0xFFU));
  k.push_back(static_cast<char>(b.store.storage_fault()));
  return k;
}

struct Tally {
  const char* test;
  std::size_t enumerated = 0;  // fault combinations of the test's class
  std::size_t simulated = 0;   // of which simulated; the rest had a wire trace or chip image
                               // identical to a simulated one, so an identical outcome
  std::size_t failures = 0;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  void fail(const char* start, const std::string& what, const std::string& faults) {
    if (++failures <= 5) ADD_FAILURE() << start << ": " << faults << ": " << what;
  }
  void report() const {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%s: %zu fault combinations checked (%zu simulated, %zu identical to a simulated one), %zu violations, %.1f s\n",
                test, enumerated, simulated, enumerated - simulated, failures, s);
    ::testing::Test::RecordProperty("fault_combinations", std::to_string(enumerated));
    ::testing::Test::RecordProperty("simulated", std::to_string(simulated));
  }
};

std::string at(const char* what, std::size_t k) { return std::string(what) + "@" + std::to_string(k); }

// S1 with a cut after each of its bytes, each followed by a reboot; the distinct states the
// reboots leave (a boot is a function of the chip image) and how many cut points left each.
std::vector<Between> s1_cut_states(Rig& rig, const Between& start, const char* name, Tally& tally,
                                   std::vector<std::size_t>& multiplicity) {
  std::vector<Between> out;
  std::unordered_map<std::string, std::size_t> seen;
  SaveTrace clean{};
  Failure fail{};
  Between mid;
  EXPECT_TRUE(rig.s1(start, {}, mid, clean, fail)) << fail.what;
  for (std::size_t k = 0; k < clean.bytes; ++k) {
    SaveTrace t{};
    if (!rig.s1(start, SaveFaults{std::nullopt, k}, mid, t, fail)) {
      tally.fail(name, fail.what, at("cut S1", k));
      continue;
    }
    const auto [it, fresh] = seen.emplace(image_key(mid), out.size());
    if (fresh) {
      out.push_back(mid);
      multiplicity.push_back(0);
    }
    ++multiplicity[it->second];
  }
  return out;
}

}  // namespace

// Every pair of power cuts: a cut after each SPI byte k1 of S1 (or none), reboot, then a cut
// after each SPI byte k2 of S2 (or none), reboot.
TEST(storage_double_fault, every_pair_of_power_cuts) {
  Tally tally{"storage_double_fault.every_pair_of_power_cuts"};
  Rig rig;
  for (const auto& [name, image] : starts()) {
    const Between start = rig.boot_from(image);
    Failure fail{};
    SaveTrace clean{};
    Between clean_mid;
    ASSERT_TRUE(rig.s1(start, {}, clean_mid, clean, fail)) << fail.what;
    std::vector<std::size_t> multiplicity;
    std::vector<Between> mids = s1_cut_states(rig, start, name, tally, multiplicity);
    mids.push_back(clean_mid);  // no cut in S1
    multiplicity.push_back(1);
    for (std::size_t i = 0; i < mids.size(); ++i) {
      const Between& mid = mids[i];
      SaveTrace t2{};
      if (!rig.s2(mid, {}, t2, fail)) tally.fail(name, fail.what, "S2 without a cut");
      ++tally.simulated;
      for (std::size_t k2 = 0; k2 < t2.bytes; ++k2) {
        SaveTrace t{};
        if (!rig.s2(mid, SaveFaults{std::nullopt, k2}, t, fail)) tally.fail(name, fail.what, at("cut S2", k2));
        ++tally.simulated;
      }
      // every cut point of S1 that left this state, x (every cut point of S2 or none)
      tally.enumerated += multiplicity[i] * (t2.bytes + 1);
    }
  }
  tally.report();
  EXPECT_EQ(tally.failures, 0U);
  EXPECT_GT(tally.simulated, 0U);
}

// Every bit flip in S1 or S2 (write or read path, any cell of the copy the save writes, on any
// single access of that cell or on all of them) paired with every power cut in S1 or S2.
// A flip's save runs once uncut, recorded frame by frame; each cut point's chip image comes from
// the model's own cut on the frame it falls in (Rig::image_after_cut), and each distinct image
// is rebooted (and, after a cut in S1, S2 runs from it).
TEST(storage_double_fault, every_bit_flip_with_every_power_cut) {
  Tally tally{"storage_double_fault.every_bit_flip_with_every_power_cut"};
  Rig rig;
  std::size_t flips_tried = 0;
  std::array<std::uint8_t, kImage> img{};
  for (const auto& [name, image] : starts()) {
    const Between start = rig.boot_from(image);
    Failure fail{};
    SaveTrace clean1{};
    Between clean_mid;
    ASSERT_TRUE(rig.s1(start, {}, clean_mid, clean1, fail)) << fail.what;
    std::array<std::uint32_t, kRecordSize> w1{}, r1{}, w2{}, r2{};
    count_accesses(rig, start, nullptr, w1, r1);
    count_accesses(rig, start, &clean_mid, w2, r2);
    std::vector<std::size_t> ignored;
    const std::vector<Between> cut_mids = s1_cut_states(rig, start, name, tally, ignored);
    std::unordered_set<std::string> s1_cut_images;  // after an S1 cut: rebooted, S2 run from it
    std::unordered_set<std::string> s2_cut_images;  // after an S2 cut: rebooted
    const ParameterSet x = Rig::s1_set(start.committed);

    for (int in = 1; in <= 2; ++in) {
      for (const Flip& flip : in == 1 ? all_flips(w1, r1) : all_flips(w2, r2)) {
        ++flips_tried;
        const std::string where = describe(flip) + " in S" + std::to_string(in);
        const SaveFaults f1 = in == 1 ? SaveFaults{flip, std::nullopt} : SaveFaults{};
        const SaveFaults f2 = in == 2 ? SaveFaults{flip, std::nullopt} : SaveFaults{};
        if (in == 2) {
          // cut in S1 (fault-free), reboot, S2 with the flip: from every distinct state
          for (const Between& m : cut_mids) {
            SaveTrace b{};
            ++tally.simulated;
            if (!rig.s2(m, f2, b, fail)) tally.fail(name, fail.what, where + ", cut in S1");
          }
          tally.enumerated += clean1.bytes;
        }
        // no cut, recorded
        std::vector<Frame> frames1, frames2;
        SaveTrace t1{}, t2{};
        Between mid;
        rig.record_frames(&frames1);
        const bool ok1 = rig.s1(start, f1, mid, t1, fail);
        rig.record_frames(&frames2);
        const bool ok2 = ok1 && rig.s2(mid, f2, t2, fail);
        rig.record_frames(nullptr);
        ++tally.enumerated;
        ++tally.simulated;
        if (!ok2) {
          tally.fail(name, fail.what, where + ", no cut");
          continue;
        }
        // cut in S1 (only with the flip in S1; with it in S2 see above)
        if (in == 1) {
          for (std::size_t k = 0; k < t1.bytes; ++k) {
            ++tally.enumerated;
            rig.image_after_cut(frames1, k, img);
            const std::string key(reinterpret_cast<const char*>(img.data()), kImage);
            if (!s1_cut_images.insert(key).second) continue;
            ++tally.simulated;
            Between m;
            SaveTrace b{};
            if (!rig.reboot_check(img, start.committed, x, m, fail, "S1") || !rig.s2(m, {}, b, fail)) {
              tally.fail(name, fail.what, where + ", " + at("cut S1", k));
            }
          }
        }
        // cut in S2
        const ParameterSet y = Rig::s2_set(mid.store.current());
        for (std::size_t k = 0; k < t2.bytes; ++k) {
          ++tally.enumerated;
          rig.image_after_cut(frames2, k, img);
          std::string key(reinterpret_cast<const char*>(img.data()), kImage);
          key.push_back(static_cast<char>(t1.result.status));
          if (!s2_cut_images.insert(key).second) continue;
          ++tally.simulated;
          Between m;
          if (!rig.reboot_check(img, mid.committed, y, m, fail, "S2")) {
            tally.fail(name, fail.what, where + ", " + at("cut S2", k));
          }
        }
      }
    }
  }
  std::printf("storage_double_fault.every_bit_flip_with_every_power_cut: %zu flips\n", flips_tried);
  tally.report();
  EXPECT_EQ(tally.failures, 0U);
  EXPECT_GT(tally.simulated, 0U);
}

// The store_ops finding's shape, one fault more than the pairs above: a write flip in S1 (on
// one write of its cell, or on every write: a weak cell), a power cut in S1 between two SPI
// frames (each frame whole: the state every attempt leaves; torn frames are the pairs' job),
// reboot, then a power cut after every SPI byte of S2, reboot.
TEST(storage_double_fault, write_flip_and_cut_then_every_cut_of_the_next_save) {
  Tally tally{"storage_double_fault.write_flip_and_cut_then_every_cut_of_the_next_save"};
  Rig rig;
  for (const auto& [name, image] : starts()) {
    const Between start = rig.boot_from(image);
    std::array<std::uint32_t, kRecordSize> w1{}, r1{};
    count_accesses(rig, start, nullptr, w1, r1);
    std::unordered_set<std::string> seen;
    Failure fail{};
    for (const Flip& flip : all_flips(w1, r1)) {
      if (flip.path != Path::Write) continue;
      std::string mosi;
      SaveTrace t1{};
      Between mid;
      rig.record_mosi(&mosi);
      if (!rig.s1(start, SaveFaults{flip, std::nullopt}, mid, t1, fail)) {
        tally.fail(name, fail.what, describe(flip) + ", no cut");
      }
      rig.record_mosi(nullptr);
      // frame boundaries: the recorded stream separates frames with '|'
      std::vector<std::size_t> bounds;
      std::size_t bytes = 0;
      for (const char c : mosi) {
        if (c == '|') {
          bounds.push_back(bytes);
        } else {
          ++bytes;
        }
      }
      for (const std::size_t k1 : bounds) {
        if (k1 >= t1.bytes) continue;  // the last boundary is the save's end: no cut
        SaveTrace a{};
        ++tally.simulated;
        if (!rig.s1(start, SaveFaults{flip, k1}, mid, a, fail)) {
          tally.fail(name, fail.what, describe(flip) + ", " + at("cut S1", k1));
          continue;
        }
        SaveTrace b{};
        const bool fresh = seen.insert(image_key(mid)).second;
        if (fresh) {
          ++tally.simulated;
          if (!rig.s2(mid, {}, b, fail)) tally.fail(name, fail.what, describe(flip) + ", " + at("cut S1", k1));
        } else {
          // same state after the reboot as an earlier case: same outcomes; only count them
          SaveTrace probe{};
          (void)rig.s2(mid, {}, probe, fail);
          tally.enumerated += probe.bytes + 1;
          continue;
        }
        tally.enumerated += b.bytes + 1;
        for (std::size_t k2 = 0; k2 < b.bytes; ++k2) {
          SaveTrace c{};
          ++tally.simulated;
          if (!rig.s2(mid, SaveFaults{std::nullopt, k2}, c, fail)) {
            tally.fail(name, fail.what, describe(flip) + ", " + at("cut S1", k1) + ", " + at("cut S2", k2));
          }
        }
      }
    }
  }
  tally.report();
  EXPECT_EQ(tally.failures, 0U);
  EXPECT_GT(tally.simulated, 0U);
}
