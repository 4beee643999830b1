// axisproof test: every ctest label under the sanitizer preset (asan), JUnit XML in out/.
#include "cli.hpp"

#include <cstdio>
#include <filesystem>

namespace ap::cli {

void add_test(CLI::App& app) {
  auto* sub = app.add_subcommand("test", "Build the asan preset (clang, ASan + UBSan) and run every test; JUnit XML under out/test/");
  static std::string label;
  static std::string preset = "asan";
  static std::string regex;
  sub->add_option("-L,--label", label, "Only tests with this ctest label (unit, property, proof, fuzz, e2e)");
  sub->add_option("-R,--regex", regex, "Only tests whose name matches this regex");
  sub->add_option("--preset", preset, "Build preset to test")->check(CLI::IsMember({"asan", "dev", "release", "cov", "fuzz"}));
  sub->final_callback([] {
    if (!ensure_built(preset)) {
      std::fprintf(stderr, "axisproof test: build of preset %s failed\n", preset.c_str());
      exit_status() = 1;
      return;
    }
    const std::string out = source_dir() + "/out/test";
    std::filesystem::create_directories(out);
    std::string cmd = "cd " + quote(source_dir()) + " && ctest --preset " + preset + " --output-junit " +
                      quote(out + "/junit-" + preset + ".xml");
    if (!label.empty()) cmd += " -L " + quote(label);
    if (!regex.empty()) cmd += " -R " + quote(regex);
    exit_status() = run(cmd) == 0 ? 0 : 1;
    std::printf("axisproof test: %s; JUnit XML: out/test/junit-%s.xml\n", exit_status() == 0 ? "PASS" : "FAIL",
                preset.c_str());
  });
}

}  // namespace ap::cli
