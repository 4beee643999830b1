// Plain replay driver: runs LLVMFuzzerTestOneInput over every file of the given files or
// directories, without libFuzzer, so regressions and corpora replay in every preset.
// An input that crashes, trips a sanitizer or fails an oracle aborts this process and
// so fails the ctest; a missing directory is fine (a target may have no regressions yet).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>
#include <algorithm>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

namespace fs = std::filesystem;

static void replay(const fs::path& p, size_t& count) {
  std::ifstream in(p, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
  ++count;
}

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize != nullptr) LLVMFuzzerInitialize(&argc, &argv);
  size_t count = 0;
  for (int i = 1; i < argc; ++i) {
    const fs::path p(argv[i]);
    if (fs::is_directory(p)) {
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(p)) {
        if (e.is_regular_file() && e.path().filename().string()[0] != '.' &&
            e.path().extension() != ".txt" && e.path().extension() != ".md") {
          files.push_back(e.path());
        }
      }
      std::sort(files.begin(), files.end());
      for (const auto& f : files) replay(f, count);
    } else if (fs::is_regular_file(p)) {
      replay(p, count);
    }
  }
  std::printf("replayed %zu inputs\n", count);
  return 0;
}
