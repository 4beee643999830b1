// End to end: the simulated PC and the simulated boards over the DDS test bus (docs/sim.md).
//   SimScenario/Bundled.Passes/NAME   every scenarios/*.scn passes (32 boards in many_boards)
//   SimOutputs.*                      the VCD and SVG of a run are well-formed and agree with it
//   SimVerdict.*                      expectations and safety checks can fail (no fixed verdicts)
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim/xy/scenario.hpp"
#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "sim/xy/run.hpp"
#include "sim/xy/trace.hpp"

namespace fs = std::filesystem;
namespace sc = ap::sim::xy::scenario;
namespace wf = ap::model::waveform;

namespace {

std::string out_root() { return std::string(AP_BINARY_DIR) + "/sim-out"; }

// Every scenarios/xy/*.scn and scenarios/xy/regressions/*.scn (the link-fault regressions of
// docs/protocol.md "Delivery" and the shrunk storms), as paths below scenarios/xy/.
std::vector<std::string> bundled() {
  std::vector<std::string> names;
  for (const char* dir : {"", "regressions/"}) {
    for (const auto& e : fs::directory_iterator(std::string(AP_SOURCE_DIR) + "/scenarios/xy/" + dir)) {
      if (e.path().extension() == ".scn") names.push_back(dir + e.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

ap::sim::xy::RunResult run(const sc::Scenario& s, const std::string& root = out_root()) {
  ap::sim::xy::RunOptions o;
  o.out_root = root;
  return ap::sim::xy::run_scenario(s, o);
}

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

class Bundled : public ::testing::TestWithParam<std::string> {};

TEST_P(Bundled, Passes) {
  const sc::Scenario s = sc::parse_file(std::string(AP_SOURCE_DIR) + "/scenarios/xy/" + GetParam() + ".scn");
  const ap::sim::xy::RunResult r = run(s);
  std::cout << ap::sim::xy::format_report(s, r);
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.vtime_us, s.duration_us);
  EXPECT_EQ(r.boards.size(), s.boards);
  // The echo checks ran (docs/sim.md "Echo checks"): the model saw every echo the bus brought.
  for (const ap::sim::xy::BoardVerdict& b : r.boards) {
    EXPECT_GT(b.echoes_from_board, 0U) << "board " << b.board;
    EXPECT_GE(b.echoes_model_checked, b.echoes_from_board) << "board " << b.board;
  }
}

INSTANTIATE_TEST_SUITE_P(SimScenario, Bundled, ::testing::ValuesIn(bundled()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           std::replace(n.begin(), n.end(), '/', '_');
                           return n;
                         });

TEST(SimOutputs, VcdAndSvgOfARunAreWellFormed) {
  // A short run: the UART decoder of models/waveform scans the line per bit, so its cost grows
  // with the square of the run length.
  const sc::Scenario s = sc::parse(
      "scenario outputs\nduration 1.5 s\nboard ble session\nat 0.3 s goto x 2 mm\n"
      "expect by 1.4 s x.status == reached\nexpect end x.pos == 2 mm\n",
      "outputs.scn");
  const std::string root = out_root() + "/outputs-test";
  const ap::sim::xy::RunResult r = run(s, root);
  ASSERT_TRUE(r.pass) << ap::sim::xy::format_report(s, r);
  const std::string dir = root + "/outputs";

  // VCD: parses, has every line the issue asks for, and agrees with the run.
  const wf::VcdDoc doc = wf::parse_vcd(slurp(dir + "/waveforms.vcd"));
  EXPECT_EQ(doc.timescale, "1ns");
  for (const char* ax : {"board.x", "board.y"}) {
    for (const char* n : {"STEP", "DIR", "ENA"}) EXPECT_NE(doc.find(ax, n), nullptr) << ax << '.' << n;
  }
  for (const char* n : {"SCK", "MOSI", "MISO", "CS_tmc_x", "CS_tmc_y", "CS_fram", "CS_enc_x", "CS_enc_y"}) {
    EXPECT_NE(doc.find("board.spi", n), nullptr) << n;
  }
  const auto* step_x = doc.find("board.x", "STEP");
  ASSERT_NE(step_x, nullptr);
  std::size_t rising = 0;
  const auto tr = doc.trace(step_x->id);
  for (std::size_t i = 1; i < tr.size(); ++i) rising += (tr[i].second == '1' && tr[i - 1].second != '1') ? 1U : 0U;
  EXPECT_EQ(rising, 3200U);   // 2 mm at 1.6 usteps/um (2 mm lead, 200 steps, 16 microsteps)
  const auto* step_y = doc.find("board.y", "STEP");
  ASSERT_NE(step_y, nullptr);
  EXPECT_LE(doc.trace(step_y->id).size(), 1U);   // Y never steps

  // UART: RX carries the PC's 41-byte command frames, TX the 65-byte echoes, both 8N1 at the
  // scenario's baud rate, and every frame starts with its start byte.
  const auto* rx = doc.find("board.uart", "RX");
  const auto* tx = doc.find("board.uart", "TX");
  ASSERT_NE(rx, nullptr);
  ASSERT_NE(tx, nullptr);
  const std::vector<std::uint8_t> rx_bytes = wf::decode_uart(doc.trace(rx->id), s.baud);
  const std::vector<std::uint8_t> tx_bytes = wf::decode_uart(doc.trace(tx->id), s.baud);
  ASSERT_FALSE(rx_bytes.empty());
  EXPECT_EQ(rx_bytes.size() % ap::xy_codec::kCommandLength, 0U);
  EXPECT_EQ(tx_bytes.size() % ap::xy_codec::kEchoLength, 0U);
  EXPECT_EQ(rx_bytes.size() / ap::xy_codec::kCommandLength, r.boards.at(0).commands);
  // Every command answered, except the one sent in the last step (the run ends before the
  // board's next tick handles it).
  EXPECT_EQ(tx_bytes.size() / ap::xy_codec::kEchoLength + 1, r.boards.at(0).commands);

  // SPI: the TMC2130 CS line carries 40-bit datagrams.
  const auto* cs = doc.find("board.spi", "CS_tmc_x");
  ASSERT_NE(cs, nullptr);
  const auto spi = wf::decode_spi(doc, cs->id, true, true);
  ASSERT_FALSE(spi.empty());
  for (const auto& t : spi) EXPECT_EQ(t.mosi.size(), 5U);

  // SVG: well-formed XML with an svg root and one polyline/path per series.
  const wf::XmlElement svg = wf::parse_xml(slurp(dir + "/plots.svg"));
  EXPECT_EQ(svg.name, "svg");
  EXPECT_GE(svg.find_all("polyline").size() + svg.find_all("path").size(), 4U);

  // trace.csv: the motion columns first, then the board-level ones; one row per tick and axis.
  std::ifstream trace(dir + "/trace.csv");
  std::string header;
  std::getline(trace, header);
  EXPECT_EQ(header.rfind(ap::sim::xy::kTraceHeader, 0), 0U);
  EXPECT_NE(header.find("lost_step_risk"), std::string::npos);
  std::size_t rows = 0;
  std::string x_edges;  // the Tab. 7-3 letters X took, in order, each run once
  for (std::string line; std::getline(trace, line);) {
    ++rows;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
    ASSERT_GE(f.size(), 14U) << line;
    ASSERT_EQ(f[12].size(), 1U) << line;
    EXPECT_NE(f[12], "-") << "the board trace shows the edge letter: " << line;
    if (f[1] == "X" && (x_edges.empty() || x_edges.back() != f[12][0])) x_edges += f[12][0];
    EXPECT_EQ(f[13], "0") << "no command of this run is refused: " << line;
  }
  EXPECT_EQ(rows, 2U * static_cast<std::size_t>(s.duration_us / 1000));
  // A goto from standstill (docs/motion.md §4): idle (I), A out of STOP, J accelerating, then
  // braking onto the target and back to idle; the run starts and ends idle.
  ASSERT_FALSE(x_edges.empty());
  EXPECT_EQ(x_edges.front(), 'I') << x_edges;
  EXPECT_EQ(x_edges.back(), 'I') << x_edges;
  EXPECT_NE(x_edges.find("IAJ"), std::string::npos) << x_edges;
}

TEST(SimVerdict, AWrongExpectationFailsWithItsLine) {
  const sc::Scenario s = sc::parse(
      "scenario wrong_expectation\nduration 3 s\nboard ble session\n"
      "at 0.5 s goto x 1 mm\nexpect at 2.5 s x.pos == 2 mm tol 1 um\nexpect by 2 s x.status == reached\n",
      "wrong_expectation.scn");
  const ap::sim::xy::RunResult r = run(s, "");
  ASSERT_FALSE(r.pass);
  ASSERT_EQ(r.failures.size(), 1U) << ap::sim::xy::format_report(s, r);
  EXPECT_NE(r.failures[0].find("wrong_expectation.scn:5"), std::string::npos) << r.failures[0];
  EXPECT_NE(r.failures[0].find("got 1000 um"), std::string::npos) << r.failures[0];
}

TEST(SimVerdict, CommandsAreIgnoredOutsideADataSession) {
  // Tab. 7-2: only an open Data Session carries commands; the same goto with the module merely
  // connected must not move the axis (and the PC sees no echoes: every frame is a gap).
  const sc::Scenario s = sc::parse(
      "scenario gated\nduration 2 s\nboard ble connected\nat 0.2 s goto x 1 mm\n"
      "expect always x.speed == 0 mm/s\nexpect end x.pos == 0 mm\nexpect end echoes == 0\nexpect end gaps >= 15\n",
      "gated.scn");
  const ap::sim::xy::RunResult r = run(s, "");
  EXPECT_TRUE(r.pass) << ap::sim::xy::format_report(s, r);
}

TEST(SimVerdict, LinkCutIsReportedAsGaps) {
  const sc::Scenario s = sc::parse(
      "scenario cut\nduration 3 s\nboard ble session\nat 1 s link cut 1 s\nexpect end gaps == 10\n", "cut.scn");
  const ap::sim::xy::RunResult r = run(s, "");
  ASSERT_TRUE(r.pass) << ap::sim::xy::format_report(s, r);
  ASSERT_EQ(r.boards.size(), 1U);
  ASSERT_EQ(r.boards[0].gaps.size(), 1U);
  EXPECT_EQ(r.boards[0].gaps[0].lost, 10U);
  EXPECT_EQ(r.boards[0].to_board.cut, 10U);
}
