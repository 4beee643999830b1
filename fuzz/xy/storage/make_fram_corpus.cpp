// Writes the seed corpus of fuzz_fram_image: small images that reach each boot branch.
// Usage: storage_make_fram_corpus <dir>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "core/xy/storage/record.hpp"

using namespace ap::xy_storage;

namespace {

std::vector<std::uint8_t> image(std::uint8_t flags) {
  std::vector<std::uint8_t> v(1 + kCopyBase[1] + kRecordSize, 0);
  v[0] = flags;
  return v;
}

void put(std::vector<std::uint8_t>& img, std::size_t copy, const ParameterSet& s, std::uint32_t seq) {
  RecordBytes r{};
  encode_record(s, seq, r);
  std::copy(r.begin(), r.end(), img.begin() + 1 + kCopyBase[copy]);
}

void save(const std::string& dir, const char* name, const std::vector<std::uint8_t>& v) {
  std::ofstream(dir + "/" + name, std::ios::binary).write(reinterpret_cast<const char*>(v.data()),
                                                           static_cast<std::streamsize>(v.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::string dir = argv[1];
  ParameterSet other = defaults();
  other.max_acceleration_um_s2 = 5000;
  other.step_counts_valid = true;
  other.step_count_x = -1000;

  save(dir, "blank", image(0));
  auto a = image(0);
  put(a, 0, defaults(), 1);
  save(dir, "only_a", a);
  auto b = image(0);
  put(b, 1, other, 7);
  save(dir, "only_b", b);
  auto ab = image(0);
  put(ab, 0, defaults(), 3);
  put(ab, 1, other, 4);
  save(dir, "a_and_b", ab);
  auto wrap = image(0);
  put(wrap, 0, defaults(), 0xFFFFFFFFU);
  put(wrap, 1, other, 0);
  save(dir, "sequence_wrap", wrap);
  auto torn = ab;
  torn[1 + kCopyBase[1] + 10] ^= 0xFF;
  save(dir, "b_torn", torn);
  auto stale = ab;  // newer copy B changed in range, CRC not updated: only the CRC rejects it
  stale[1 + kCopyBase[1] + entry(ParamId::MaxAcceleration).offset] ^= 0x01;
  save(dir, "b_stale_crc", stale);
  auto range = image(3);  // CRCs recomputed by the target
  put(range, 0, defaults(), 5);
  put(range, 1, other, 6);
  range[1 + kCopyBase[1] + entry(ParamId::RunCurrent).offset] = 40;
  save(dir, "b_out_of_range", range);
  auto ms = image(1);
  put(ms, 0, other, 9);
  ms[1 + entry(ParamId::Microsteps).offset] = 3;
  save(dir, "a_microsteps_3", ms);
  std::printf("wrote corpus to %s\n", dir.c_str());
  return 0;
}
