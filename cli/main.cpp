// axisproof: the verification harness's command line. main() is in the library ap_cli with the
// shared commands, so a project outside the tree links it with its own profiles' adapters and
// table (ap_add_axisproof, docs/profiles.md "Your own firmware").
// Usage errors (unknown subcommand or option) print one line and exit 2, so scripts can
// tell a typo from a failing gate (exit 1).
#include "cli.hpp"
#include "profile.hpp"

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  CLI::App app{"axisproof: verification harness for stepper-motor positioning firmware"};
  app.set_version_flag("--version", std::string("axisproof ") + AP_VERSION);
  app.require_subcommand(1, 1);
  app.allow_extras(false);

  ap::cli::add_gate(app);
  ap::cli::add_test(app);
  ap::cli::add_prove(app);
  ap::cli::add_fuzz(app);
  ap::cli::add_sim(app);
  ap::cli::add_bench(app);
  ap::cli::add_frame(app);
  ap::cli::add_panel(app);
  // Subcommands only one profile has, from its entry (add_commands, cli/profile.hpp).
  for (const auto& p : ap::cli::profiles()) {
    if (p.add_commands != nullptr) p.add_commands(app);
  }

  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const auto* sub : app.get_subcommands({})) known = known || sub->get_name() == argv[1];
    if (!known) {
      std::fprintf(stderr, "axisproof: unknown subcommand '%s' (see axisproof --help)\n", argv[1]);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::CallForVersion&) {
    std::printf("axisproof %s\n", AP_VERSION);
    return 0;
  } catch (const CLI::Success&) {
    return 0;  // an option that answered by itself (--profile list)
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    for (char& c : what) {
      if (c == '\n') c = ' ';
    }
    // One line, naming what was wrong; --help lists what is allowed.
    std::fprintf(stderr, "axisproof: %s (see axisproof --help)\n", what.c_str());
    return 2;
  }
  return ap::cli::exit_status();
}
