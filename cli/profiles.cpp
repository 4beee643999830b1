// The profiles the harness knows (docs/profiles.md). A new controller adds one line here and
// its adapter file, profile_<name>.cpp.
#include <cstdio>

#include "profile.hpp"

namespace ap::cli {

const std::vector<Profile>& profiles() {
  static const std::vector<Profile> all = {xy_profile(), unit3_profile(), hc08_profile()};
  return all;
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
      ->default_val("xy")
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
