// Report writers of the release gate: the verdict table, JUnit XML, out/gate/report.md and
// report.html, and the release manifest (out/release/manifest.json, MANIFEST.md).
#include "cli.hpp"
#include "gate.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace ap::cli::gate {

const char* to_string(Result r) {
  switch (r) {
    case Result::Pass: return "PASS";
    case Result::Fail: return "FAIL";
    case Result::NotRun: return "NOT RUN";
  }
  return "?";
}

namespace {

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&apos;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += c;
    } else if (c == '\n') {
      o += "\\n";
    } else if (static_cast<unsigned char>(c) < 0x20) {
      o += ' ';
    } else {
      o += c;
    }
  }
  return o;
}

std::string md_cell(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '|') o += "\\|";
    else if (c == '\n') o += ' ';
    else o += c;
  }
  return o;
}

std::string fmt_number(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", s);
  return buf;
}

std::string fmt_seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f s", s);
  return buf;
}

void md_table(std::ostream& out, const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  out << "|";
  for (const auto& h : head) out << " " << h << " |";
  out << "\n|";
  for (size_t i = 0; i < head.size(); ++i) out << "---|";
  out << "\n";
  for (const auto& r : rows) {
    out << "|";
    for (const auto& c : r) out << " " << md_cell(c) << " |";
    out << "\n";
  }
}

void html_table(std::ostream& out, const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  out << "<table>\n<tr>";
  for (const auto& h : head) out << "<th>" << xml_escape(h) << "</th>";
  out << "</tr>\n";
  for (const auto& r : rows) {
    out << "<tr>";
    for (const auto& c : r) {
      std::string cls;
      if (c == "PASS" || c.rfind("killed", 0) == 0) cls = " class=\"pass\"";
      else if (c == "FAIL" || c == "SURVIVED" || c.rfind("INVALID", 0) == 0 || c == "FAILED") cls = " class=\"fail\"";
      else if (c == "NOT RUN") cls = " class=\"notrun\"";
      out << "<td" << cls << ">" << xml_escape(c) << "</td>";
    }
    out << "</tr>\n";
  }
  out << "</table>\n";
}

std::vector<std::vector<std::string>> stage_rows(const Run& run) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : run.rows) {
    rows.push_back({r.stage, to_string(r.outcome.result), fmt_seconds(r.seconds), r.outcome.key,
                    r.log.empty() ? "" : r.log});
  }
  return rows;
}

}  // namespace

void print_table(const Run& run) {
  std::printf("\n%-24s %-8s %9s  %s\n", "stage", "result", "time", "key figure");
  for (const auto& r : run.rows) {
    std::printf("%-24s %-8s %8.1fs  %s\n", r.stage.c_str(), to_string(r.outcome.result), r.seconds,
                r.outcome.key.c_str());
  }
  std::printf("%-24s %-8s %8.1fs\n", "total", "", run.seconds);
  std::printf("\nverdict (profile %s): %s\n", run.profile.c_str(), run.pass ? "PASS" : "FAIL");
}

bool write_junit(const Run& run, const std::string& file) {
  if (fs::path(file).has_parent_path()) fs::create_directories(fs::path(file).parent_path());
  std::ofstream out(file);
  if (!out) return false;
  int failures = 0;
  for (const auto& r : run.rows) failures += r.outcome.result != Result::Pass;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<testsuites name=\"axisproof gate\" tests=\"" << run.rows.size() << "\" failures=\"" << failures
      << "\" time=\"" << run.seconds << "\">\n";
  out << "  <testsuite name=\"axisproof.gate\" tests=\"" << run.rows.size() << "\" failures=\"" << failures
      << "\" errors=\"0\" skipped=\"0\" time=\"" << run.seconds << "\" timestamp=\"" << xml_escape(run.date) << "\">\n";
  for (const auto& r : run.rows) {
    out << "    <testcase classname=\"axisproof.gate\" name=\"" << xml_escape(r.stage) << "\" time=\"" << r.seconds << "\">";
    if (r.outcome.result == Result::Fail) {
      out << "\n      <failure message=\"FAIL: " << xml_escape(r.outcome.key) << "\" type=\"FAIL\">"
          << xml_escape(r.log.empty() ? r.outcome.key : "log: " + r.log) << "</failure>\n    ";
    } else if (r.outcome.result == Result::NotRun) {
      // NOT RUN fails the gate, so it is a failure here too, never a skip.
      out << "\n      <failure message=\"NOT RUN: " << xml_escape(r.outcome.key) << "\" type=\"NOT RUN\"/>\n    ";
    } else {
      out << "<system-out>" << xml_escape(r.outcome.key) << "</system-out>";
    }
    out << "</testcase>\n";
  }
  out << "  </testsuite>\n</testsuites>\n";
  return static_cast<bool>(out);
}

namespace {
const char* kTimesNote =
    "The asan build's targets by the seconds their steps took (.ninja_log of the last build of each output: compile and "
    "link, CPU seconds on up to two cores at once), and the slowest tests of the test stages (ctest's own times). "
    "Every part's time is also in times.tsv, which balances the next sharded run (docs/ci.md).";

std::string shard_words(const std::string& shard) {
  return shard.rfind("joined", 0) == 0 ? shard : "shard " + shard + " (its part of the gate; `axisproof gate join` gives the verdict)";
}

// What the release artifact holds for the MCU: the size table says whether images were linked.
std::string image_note(const Details& d) {
  if (d.m4_size_md.find("## Linked images") != std::string::npos) {
    return "The release artifact holds the linked images (the STM32L476 board's and the QEMU machine's, with their map "
           "files) beside the core's Cortex-M4 static libraries; docs/qemu.md.";
  }
  return "This profile has no MCU port yet (startup code, linker script, peripheral layer): the release artifact holds "
         "its core as Cortex-M4 static libraries, not a firmware image.";
}
}  // namespace

void write_reports(const Run& run, const std::string& dir) {
  fs::create_directories(dir);
  const auto& d = run.details;
  const std::vector<std::string> stage_head = {"stage", "result", "time", "key figure", "log"};
  const std::vector<std::string> proof_head = {"obligation", "result", "seconds", "method"};
  const std::vector<std::string> fuzz_head = {"target", "executions", "exec/s", "corpus", "coverage (edges)", "findings"};
  const std::vector<std::string> mut_head = {"mutant", "models", "result", "seconds"};
  const std::vector<std::string> cov_head = {"file", "lines", "line %", "branches", "branch %"};
  const std::vector<std::string> build_head = {"build target (asan)", "steps", "seconds", "share"};
  const std::vector<std::string> test_head = {"test", "stage", "seconds", "share of its stage"};

  std::ofstream md(dir + "/report.md");
  md << "# axisproof release gate: " << (run.pass ? "PASS" : "FAIL") << "\n\n";
  md << "Profile " << run.profile << (run.shard == "1/1" ? "" : ", " + shard_words(run.shard)) << ". axisproof " << run.version << ", commit " << run.git_hash << ", " << run.date << ", total "
     << fmt_seconds(run.seconds) << ". A stage that could not run is NOT RUN and fails the gate.\n\n";
  md << "## Stages\n\n";
  md_table(md, stage_head, stage_rows(run));
  md << "\n## Proofs\n\n";
  if (d.proofs.empty()) md << "No proof table (the proofs stage did not run).\n";
  else md_table(md, proof_head, d.proofs);
  md << "\n## Fuzz smoke\n\n";
  if (d.fuzz.empty()) md << "No fuzz run.\n";
  else md_table(md, fuzz_head, d.fuzz);
  md << "\n## Coverage (test suite, llvm-cov)\n\n";
  md << (d.coverage_summary.empty() ? "No coverage figures (the coverage stage did not run)." : d.coverage_summary) << "\n\n";
  if (!d.coverage.empty()) md_table(md, cov_head, d.coverage);
  md << "\n## Mutation suite\n\n";
  md << (d.mutation_summary.empty() ? "No mutation results (the mutation stage did not run)." : d.mutation_summary) << "\n\n";
  if (!d.mutants.empty()) md_table(md, mut_head, d.mutants);
  md << "\n## Cortex-M4 build\n\n";
  if (d.m4_size_md.empty()) {
    md << "No size table (the cortex-m4 stage did not run).\n";
  } else {
    std::string body = d.m4_size_md;
    if (body.rfind("# ", 0) == 0) body = body.substr(body.find('\n') + 1);  // drop its own title
    md << body;
  }
  md << "\n" << image_note(d) << "\n";
  md << "\n## Where the time went\n\n" << kTimesNote << "\n\n";
  if (!d.build_times.empty()) md_table(md, build_head, d.build_times);
  md << "\n";
  if (!d.test_times.empty()) md_table(md, test_head, d.test_times);
  md << "\n## Scenario plots\n\n";
  if (d.plots.empty()) md << "No SVG plots under out/sim/ (run `axisproof sim`).\n";
  for (const auto& p : d.plots) md << "- [" << p << "](" << p << ")\n";

  std::ofstream html(dir + "/report.html");
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>axisproof gate: " << (run.pass ? "PASS" : "FAIL")
       << "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:80em}table{border-collapse:collapse;margin:1em 0}"
          "td,th{border:1px solid #bbb;padding:.25em .6em;text-align:left;vertical-align:top}th{background:#eee}"
          ".pass{background:#dfd}.fail{background:#fdd}.notrun{background:#fed}pre{background:#f6f6f6;padding:1em}"
          "h1 span.pass,h1 span.fail{padding:0 .3em}</style></head><body>\n";
  html << "<h1>axisproof release gate: <span class=\"" << (run.pass ? "pass" : "fail") << "\">" << (run.pass ? "PASS" : "FAIL")
       << "</span></h1>\n<p>Profile " << xml_escape(run.profile) << xml_escape(run.shard == "1/1" ? "" : ", " + shard_words(run.shard)) << ". axisproof " << xml_escape(run.version) << ", commit " << xml_escape(run.git_hash) << ", "
       << xml_escape(run.date) << ", total " << fmt_seconds(run.seconds)
       << ". A stage that could not run is NOT RUN and fails the gate.</p>\n";
  html << "<h2>Stages</h2>\n";
  {
    auto rows = stage_rows(run);
    html_table(html, stage_head, rows);
  }
  html << "<h2>Proofs</h2>\n";
  if (d.proofs.empty()) html << "<p>No proof table (the proofs stage did not run).</p>\n";
  else html_table(html, proof_head, d.proofs);
  html << "<h2>Fuzz smoke</h2>\n";
  if (d.fuzz.empty()) html << "<p>No fuzz run.</p>\n";
  else html_table(html, fuzz_head, d.fuzz);
  html << "<h2>Coverage (test suite, llvm-cov)</h2>\n<p>"
       << xml_escape(d.coverage_summary.empty() ? "No coverage figures (the coverage stage did not run)." : d.coverage_summary)
       << (d.coverage_summary.empty() ? "" : " <a href=\"../coverage/tests/html/index.html\">line-by-line report</a>") << "</p>\n";
  if (!d.coverage.empty()) html_table(html, cov_head, d.coverage);
  html << "<h2>Mutation suite</h2>\n<p>"
       << xml_escape(d.mutation_summary.empty() ? "No mutation results (the mutation stage did not run)." : d.mutation_summary)
       << "</p>\n";
  if (!d.mutants.empty()) html_table(html, mut_head, d.mutants);
  html << "<h2>Cortex-M4 build</h2>\n";
  html << "<pre>" << xml_escape(d.m4_size_md.empty() ? "No size table (the cortex-m4 stage did not run)." : d.m4_size_md)
       << "</pre>\n<p>" << xml_escape(image_note(d)) << "</p>\n";
  html << "<h2>Where the time went</h2>\n<p>" << xml_escape(kTimesNote) << "</p>\n";
  if (!d.build_times.empty()) html_table(html, build_head, d.build_times);
  if (!d.test_times.empty()) html_table(html, test_head, d.test_times);
  html << "<h2>Scenario plots</h2>\n";
  if (d.plots.empty()) html << "<p>No SVG plots under out/sim/ (run <code>axisproof sim</code>).</p>\n";
  for (const auto& p : d.plots) {
    html << "<figure><img src=\"" << xml_escape(p) << "\" alt=\"" << xml_escape(p) << "\" style=\"max-width:100%\">"
         << "<figcaption><a href=\"" << xml_escape(p) << "\">" << xml_escape(p) << "</a></figcaption></figure>\n";
  }
  html << "</body></html>\n";
}

void write_manifest(const Run& run, const std::string& release) {
  fs::create_directories(release);
  auto first_line = [](const std::string& cmd) {
    int st = 0;
    std::string s = run_capture(cmd + " 2>/dev/null | head -1", &st);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s.empty() ? std::string("not installed") : s;
  };
  const std::string gcc = first_line("g++ --version");
  const std::string clang = first_line("clang++ --version");
  const std::string arm = first_line("arm-none-eabi-g++ --version");
  std::vector<std::string> libs;
  std::error_code ec;
  const std::string& tag = run.size_tag;
  if (fs::is_directory(release + "/" + tag, ec)) {
    for (const auto& e : fs::directory_iterator(release + "/" + tag, ec)) libs.push_back(tag + "/" + e.path().filename().string());
  }
  std::sort(libs.begin(), libs.end());
  // The linked images and their maps (docs/qemu.md), where the profile has an MCU port.
  std::string images;
  for (const auto& l : libs) {
    if (l.size() > 4 && (l.ends_with(".elf") || l.ends_with(".map"))) images += (images.empty() ? "" : ", ") + l;
  }
  const std::string port = images.empty() ? "not included: this profile has no startup code, linker script or peripheral layer yet"
                                          : "images " + images + " (docs/qemu.md)";
  std::ofstream j(release + "/manifest.json");
  j << "{\n  \"name\": \"axisproof\",\n  \"version\": \"" << json_escape(run.version) << "\",\n  \"git\": \""
    << json_escape(run.git_hash) << "\",\n  \"profile\": \"" << json_escape(run.profile) << "\",\n  \"date\": \"" << json_escape(run.date) << "\",\n  \"verdict\": \""
    << (run.pass ? "PASS" : "FAIL") << "\",\n  \"compilers\": {\n    \"host-gcc\": \"" << json_escape(gcc)
    << "\",\n    \"host-clang\": \"" << json_escape(clang) << "\",\n    \"arm-none-eabi\": \"" << json_escape(arm)
    << "\"\n  },\n  \"m4_flags\": \"-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -Os -Werror -fno-exceptions -fno-rtti\",\n"
    << "  \"m4_libraries\": [";
  for (size_t i = 0; i < libs.size(); ++i) j << (i ? ", " : "") << "\"" << json_escape(libs[i]) << "\"";
  j << "],\n  \"mcu_port\": \"" << json_escape(port) << "\",\n"
    << "  \"stages\": [\n";
  for (size_t i = 0; i < run.rows.size(); ++i) {
    const auto& r = run.rows[i];
    j << "    {\"stage\": \"" << json_escape(r.stage) << "\", \"result\": \"" << to_string(r.outcome.result)
      << "\", \"seconds\": " << fmt_number(r.seconds) << ", \"key\": \"" << json_escape(r.outcome.key)
      << "\"}" << (i + 1 < run.rows.size() ? "," : "") << "\n";
  }
  j << "  ]\n}\n";

  std::ofstream m(release + "/MANIFEST.md");
  m << "# axisproof release artifact\n\n";
  m << "- profile: " << run.profile << "\n- version: " << run.version << "\n- git: " << run.git_hash << "\n- date: " << run.date
    << "\n- gate verdict: " << (run.pass ? "PASS" : "FAIL") << "\n- host gcc: " << gcc << "\n- host clang: " << clang
    << "\n- arm-none-eabi: " << arm << "\n- Cortex-M4 libraries (" << tag << "/): ";
  for (size_t i = 0; i < libs.size(); ++i) m << (i ? ", " : "") << libs[i];
  m << (libs.empty() ? "none" : "") << "\n- size table: " << tag << "-size.md\n"
    << "- MCU port: " << port << "\n\n";
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : run.rows) rows.push_back({r.stage, to_string(r.outcome.result), fmt_seconds(r.seconds), r.outcome.key});
  md_table(m, {"stage", "result", "time", "key figure"}, rows);
}

}  // namespace ap::cli::gate
