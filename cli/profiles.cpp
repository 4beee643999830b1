// The profile table's lookups (docs/profiles.md). The table itself is generated from the
// profiles' declarations (cmake/AxisproofProfiles.cmake).
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "profile.hpp"

namespace ap::cli {

Profile declared(Profile adapter, std::string_view name, std::string_view title, std::string_view seed,
                 std::string_view mcu, std::string_view size_tag, bool is_default, std::vector<std::string_view> dirs,
                 std::vector<std::string_view> coverage) {
  adapter.name = name;
  adapter.title = title;
  adapter.seed = seed;
  adapter.mcu = mcu;
  adapter.size_tag = size_tag;
  adapter.is_default = is_default;
  adapter.dirs = std::move(dirs);
  adapter.coverage_paths = std::move(coverage);
  return adapter;
}

std::string scenarios_dir(const Profile& p) { return "scenarios/" + std::string(p.name); }

const Profile& default_profile() {
  const auto& all = profiles();
  if (all.empty()) throw std::logic_error("no profile is declared (profiles/*.cmake)");
  for (const auto& p : all) {
    if (p.is_default) return p;
  }
  return all.front();
}

const Profile* find_profile(std::string_view name) {
  for (const auto& p : profiles()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

void add_profile_option(CLI::App* sub, std::string& name) {
  std::vector<std::string> names{"list"};
  std::string known;
  for (const auto& p : profiles()) {
    names.emplace_back(p.name);
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  // `--profile list` answers at once, before the subcommand's other options are checked.
  sub->add_option("--profile", name, "Firmware profile (" + known + "; `list` shows them, docs/profiles.md)")
      ->default_val(std::string(default_profile().name))
      ->check(CLI::IsMember(names))
      ->each([](const std::string& v) {
        if (v == "list") {
          print_profiles();
          throw CLI::Success();
        }
      });
}

void print_profiles() {
  std::printf("%-8s %-36s %-32s %s\n", "profile", "controller", "requirements", "MCU (size check)");
  for (const auto& p : profiles()) {
    std::printf("%-8.*s %-36.*s %-32.*s %.*s\n", static_cast<int>(p.name.size()), p.name.data(),
                static_cast<int>(p.title.size()), p.title.data(), static_cast<int>(p.seed.size()), p.seed.data(),
                static_cast<int>(p.mcu.size()), p.mcu.data());
  }
}

}  // namespace ap::cli
