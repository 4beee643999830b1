// models/waveform: the VCD and SVG writers produce well-formed files that parse back to what
// was written (UART bytes, SPI transfers, STEP pulses, plotted series).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"

namespace wf = ap::model::waveform;

namespace {

std::size_t count_rising(const std::vector<std::pair<std::uint64_t, char>>& tr) {
  std::size_t n = 0;
  for (std::size_t i = 1; i < tr.size(); ++i) {
    n += tr[i - 1].second == '0' && tr[i].second == '1' ? 1U : 0U;
  }
  return n;
}

}  // namespace

TEST(waveform_vcd, GenericWriterSortsAndParsesBack) {
  std::ostringstream os;
  {
    wf::VcdWriter w(os);
    const int a = w.wire("top.sub", "a");
    const int bus = w.wire("top", "bus", 8, 0x5A);
    const int c = w.wire("top.sub", "c", 1, wf::kHighZ);
    w.set(300, a, 1);
    w.set(100, bus, 0xFF);
    w.set(100, a, 1);
    w.set(200, a, 1);   // no change: dropped
    w.set(400, c, 0);
    w.set(500, bus, 3);
    w.finish();
  }
  const wf::VcdDoc d = wf::parse_vcd(os.str());
  EXPECT_EQ(d.timescale, "1ns");
  ASSERT_EQ(d.vars.size(), 3U);
  const auto* a = d.find("top.sub", "a");
  const auto* bus = d.find("top", "bus");
  ASSERT_TRUE(a && bus);
  EXPECT_EQ(bus->width, 8U);
  const auto ta = d.trace(a->id);
  ASSERT_EQ(ta.size(), 2U);   // initial 0, then 1 at 100
  EXPECT_EQ(ta[1], (std::pair<std::uint64_t, char>{100, '1'}));
  std::vector<std::string> bus_values;
  for (const auto& ch : d.changes) {
    if (ch.id == bus->id) bus_values.push_back(ch.value);
  }
  EXPECT_EQ(bus_values, (std::vector<std::string>{"1011010", "11111111", "11"}));
  EXPECT_NE(os.str().find("z"), std::string::npos);
}

TEST(waveform_vcd, ManyWiresGetUniqueSafeIds) {
  std::ostringstream os;
  {
    wf::VcdWriter w(os);
    for (int i = 0; i < 300; ++i) {
      const int s = w.wire("top", std::string("w").append(std::to_string(i)));
      w.set(static_cast<std::uint64_t>(i), s, 1);
    }
    w.finish();
  }
  const auto d = wf::parse_vcd(os.str());
  ASSERT_EQ(d.vars.size(), 300U);
  std::set<std::string> ids;
  for (const auto& v : d.vars) {
    EXPECT_EQ(v.id.find_first_of("#$ "), std::string::npos) << v.id;
    ids.insert(v.id);
  }
  EXPECT_EQ(ids.size(), 300U);
  EXPECT_EQ(d.changes.size(), 600U);   // 300 initial values + 300 changes
}

TEST(waveform_vcd, StreamingFlushRejectsChangesInThePast) {
  std::ostringstream os;
  wf::VcdWriter w(os);
  const int a = w.wire("t", "a");
  w.set(10, a, 1);
  w.flush(50);
  EXPECT_THROW(w.set(40, a, 0), std::logic_error);
  EXPECT_THROW(w.wire("t", "late"), std::logic_error);
  w.set(60, a, 0);
  w.finish();
  EXPECT_THROW(w.set(70, a, 1), std::logic_error);
  EXPECT_NO_THROW(wf::parse_vcd(os.str()));
}

TEST(waveform_vcd, ParserRejectsMalformedFiles) {
  const std::string good =
      "$timescale 1ns $end\n$scope module m $end\n$var wire 1 ! a $end\n$var wire 4 \" b $end\n$upscope $end\n"
      "$enddefinitions $end\n#0\n$dumpvars\n0!\nb0 \"\n$end\n#5\n1!\n";
  EXPECT_NO_THROW(wf::parse_vcd(good));
  EXPECT_THROW(wf::parse_vcd("$timescale 1ns\n$enddefinitions $end\n"), wf::VcdParseError);   // no $end
  EXPECT_THROW(wf::parse_vcd(good + "1#\n"), wf::VcdParseError);             // undeclared id
  EXPECT_THROW(wf::parse_vcd(good + "#3\n0!\n"), wf::VcdParseError);         // time goes back
  EXPECT_THROW(wf::parse_vcd(good + "b10101 \"\n"), wf::VcdParseError);      // too wide
  EXPECT_THROW(wf::parse_vcd(good.substr(0, 60)), wf::VcdParseError);       // truncated header
  EXPECT_THROW(wf::parse_vcd("$scope module m $end\n$enddefinitions $end\n"), wf::VcdParseError);
}

RC_GTEST_PROP(waveform_board, UartBytesRoundTrip, ()) {
  const auto bytes = *rc::gen::container<std::vector<std::uint8_t>>(*rc::gen::inRange<std::size_t>(1, 40),
                                                                   rc::gen::arbitrary<std::uint8_t>());
  const std::uint32_t baud = *rc::gen::element<std::uint32_t>(9600, 115200, 921600, 1000000);
  wf::BoardWaveformConfig cfg;
  cfg.uart_baud = baud;
  std::ostringstream os;
  {
    wf::BoardWaveforms b(os, cfg);
    const std::uint64_t end = b.uart(wf::BoardWaveforms::Uart::rx, 1000, bytes);
    // A second message queued behind the first on TX, and one on RX that must wait.
    b.uart(wf::BoardWaveforms::Uart::tx, 500, bytes);
    b.uart(wf::BoardWaveforms::Uart::rx, 0, std::vector<std::uint8_t>{0x55});
    RC_ASSERT(end == 1000 + (10 * bytes.size() * 1'000'000'000ULL + baud / 2) / baud);   // rounded once, no drift
    b.finish();
  }
  const wf::VcdDoc d = wf::parse_vcd(os.str());
  const auto* rx = d.find("board.uart", "RX");
  const auto* tx = d.find("board.uart", "TX");
  RC_ASSERT(rx != nullptr && tx != nullptr);
  auto expect_rx = bytes;
  expect_rx.push_back(0x55);
  RC_ASSERT(wf::decode_uart(d.trace(rx->id), baud) == expect_rx);
  RC_ASSERT(wf::decode_uart(d.trace(tx->id), baud) == bytes);
}

TEST(waveform_board, UartFrameTiming) {
  // 115200 baud: 10 bits of 8680.6 ns; 'A' = 0x41 -> 0 (start) 1 0 0 0 0 0 1 0, 1 (stop).
  std::ostringstream os;
  {
    wf::BoardWaveforms b(os, wf::BoardWaveformConfig{});
    const std::vector<std::uint8_t> a{'A'};
    EXPECT_EQ(b.uart(wf::BoardWaveforms::Uart::tx, 0, a), 86806U);
    b.finish();
  }
  const auto d = wf::parse_vcd(os.str());
  const auto tr = d.trace(d.find("board.uart", "TX")->id);
  const std::vector<std::pair<std::uint64_t, char>> want{{0, '1'}, {0, '0'}, {8681, '1'}, {17361, '0'},
                                                         {60764, '1'}, {69444, '0'}, {78125, '1'}};
  EXPECT_EQ(tr, want);
}

RC_GTEST_PROP(waveform_board, SpiTransfersRoundTripInEveryMode, ()) {
  const auto mosi = *rc::gen::container<std::vector<std::uint8_t>>(*rc::gen::inRange<std::size_t>(1, 8),
                                                                  rc::gen::arbitrary<std::uint8_t>());
  std::vector<std::uint8_t> miso(mosi.size());
  for (auto& b : miso) b = *rc::gen::arbitrary<std::uint8_t>();
  const bool cpol = *rc::gen::arbitrary<bool>();
  const bool cpha = *rc::gen::arbitrary<bool>();
  wf::BoardWaveformConfig cfg;
  cfg.spi_devices = {{"dev", cpol, cpha}, {"other", !cpol, cpha}};
  std::ostringstream os;
  {
    wf::BoardWaveforms b(os, cfg);
    b.spi(1, 0, mosi, miso);      // another device first, other clock polarity
    b.spi(0, 10, mosi, miso);     // queued behind it
    b.spi(0, 10, miso, mosi);
    b.finish();
  }
  const wf::VcdDoc d = wf::parse_vcd(os.str());
  const auto got = wf::decode_spi(d, d.find("board.spi", "CS_dev")->id, cpol, cpha);
  RC_ASSERT(got.size() == 2U);
  RC_ASSERT(got[0].mosi == mosi);
  RC_ASSERT(got[0].miso == miso);
  RC_ASSERT(got[1].mosi == miso);
  RC_ASSERT(got[1].miso == mosi);
  const auto other = wf::decode_spi(d, d.find("board.spi", "CS_other")->id, !cpol, cpha);
  RC_ASSERT(other.size() == 1U && other[0].mosi == mosi);
}

TEST(waveform_board, TmcIholdIrunDatagram) {
  // §9.3: IHOLD_IRUN write with IRUN = 12, mode 3 (the TMC2130 default in the config).
  std::ostringstream os;
  wf::BoardWaveforms b(os, wf::BoardWaveformConfig{});
  const std::vector<std::uint8_t> dg{0x90, 0x00, 0x07, 0x0C, 0x03};
  const std::uint64_t end = b.spi(b.spi_device("tmc_x"), 1000, dg);
  EXPECT_EQ(end, 1000U + 500U + 500U + 40U * 1000U + 500U);   // 1 MHz: 40 bits of 1 us
  b.finish();
  const auto d = wf::parse_vcd(os.str());
  const auto got = wf::decode_spi(d, d.find("board.spi", "CS_tmc_x")->id, true, true);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].mosi, dg);
  EXPECT_EQ(got[0].miso, std::vector<std::uint8_t>(5, 0));
  EXPECT_THROW((void)b.spi_device("nope"), std::out_of_range);
}

TEST(waveform_board, StepDirEnaPerAxis) {
  std::ostringstream os;
  {
    wf::BoardWaveforms b(os, wf::BoardWaveformConfig{});
    b.ena(0, 0, true);
    b.dir(0, 0, true);
    for (std::uint64_t i = 0; i < 100; ++i) b.step(0, 10'000 + i * 62'500);
    b.dir(1, 5'000, true);
    for (std::uint64_t i = 0; i < 30; ++i) b.step(1, 7'000 + i * 100'000);
    b.flush(3'000'000);   // streaming in the middle of a run
    b.ena(0, 9'000'000, false);
    b.finish();
  }
  const auto d = wf::parse_vcd(os.str());
  for (const char* ax : {"board.x", "board.y"}) {
    for (const char* sig : {"STEP", "DIR", "ENA"}) {
      ASSERT_NE(d.find(ax, sig), nullptr) << ax << '.' << sig;
    }
  }
  EXPECT_EQ(count_rising(d.trace(d.find("board.x", "STEP")->id)), 100U);
  EXPECT_EQ(count_rising(d.trace(d.find("board.y", "STEP")->id)), 30U);
  const auto ena = d.trace(d.find("board.x", "ENA")->id);
  ASSERT_EQ(ena.size(), 3U);
  EXPECT_EQ(ena.back(), (std::pair<std::uint64_t, char>{9'000'000, '0'}));
}

// ------------------------------------------------------------------------------------------- SVG

namespace {

wf::MotionTrace trapezoid(double a_mm_s2) {
  // 20 mm at 10 mm/s from rest (thesis Obr. 9-2).
  wf::MotionTrace t;
  t.label = "a = " + std::to_string(static_cast<int>(a_mm_s2)) + " mm/s^2 <&>";
  const double v = 10.0, d = 20.0;
  const double ta = std::min(v / a_mm_s2, std::sqrt(d / a_mm_s2));
  const double vp = a_mm_s2 * ta;
  const double tc = (d - vp * ta) / vp;
  const double total = 2 * ta + tc;
  for (double s = 0; s <= total + 1e-9; s += 0.001) {
    double x, sp;
    if (s < ta) { sp = a_mm_s2 * s; x = 0.5 * a_mm_s2 * s * s; }
    else if (s < ta + tc) { sp = vp; x = 0.5 * vp * ta + vp * (s - ta); }
    else { const double r = total - s; sp = a_mm_s2 * r; x = d - 0.5 * a_mm_s2 * r * r; }
    t.t_s.push_back(s);
    t.pos_mm.push_back(x);
    t.speed_mm_s.push_back(sp);
  }
  return t;
}

std::vector<std::pair<double, double>> points_of(const wf::XmlElement& poly) {
  std::vector<std::pair<double, double>> out;
  std::istringstream in(poly.attrs.at("points"));
  std::string pair;
  while (in >> pair) {
    const auto comma = pair.find(',');
    if (comma == std::string::npos) throw std::runtime_error("bad point " + pair);
    out.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  return out;
}

}  // namespace

TEST(waveform_svg, MotionPlotIsWellFormedWithAllSeries) {
  const std::vector<wf::MotionTrace> traces{trapezoid(5), trapezoid(10), trapezoid(20)};
  std::ostringstream os;
  wf::write_motion_svg(os, "20 mm absolute move, v = 10 mm/s", traces);
  const wf::XmlElement svg = wf::parse_xml(os.str());
  EXPECT_EQ(svg.name, "svg");
  EXPECT_EQ(svg.attrs.at("xmlns"), "http://www.w3.org/2000/svg");
  std::istringstream vb(svg.attrs.at("viewBox"));
  double x0, y0, w, h;
  vb >> x0 >> y0 >> w >> h;
  ASSERT_GT(w, 0);
  ASSERT_EQ(svg.find_all("title").size(), 1U);
  const auto panels = svg.find_all("g");
  std::size_t n_panels = 0;
  for (const auto* g : panels) n_panels += g->attrs.count("class") != 0U && g->attrs.at("class") == "panel" ? 1U : 0U;
  EXPECT_EQ(n_panels, 2U);
  const auto polys = svg.find_all("polyline");
  ASSERT_EQ(polys.size(), 6U);
  EXPECT_EQ(polys[0]->attrs.at("data-label"), "a = 5 mm/s^2 <&>");
  for (const auto* p : polys) {
    const auto pts = points_of(*p);
    ASSERT_GT(pts.size(), 100U);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      EXPECT_GE(pts[i].first, x0);
      EXPECT_LE(pts[i].first, x0 + w);
      EXPECT_GE(pts[i].second, y0);
      EXPECT_LE(pts[i].second, y0 + h);
      if (i > 0) {
        EXPECT_GE(pts[i].first, pts[i - 1].first);
      }
    }
  }
  // The position of a 20 mm move ends at the top of its panel, the speed at the bottom.
  const auto pos = points_of(*polys[0]);
  const auto spd = points_of(*polys[3]);
  EXPECT_LT(pos.back().second, pos.front().second);
  EXPECT_NEAR(spd.back().second, spd.front().second, 1.0);
}

TEST(waveform_svg, LongSeriesAreDecimatedKeepingTheEnvelope) {
  wf::Series s{"noise", {}, {}, {}, false};
  for (int i = 0; i < 1'000'000; ++i) {
    s.x.push_back(i * 1e-5);
    s.y.push_back(i % 1000 == 500 ? 100.0 : std::sin(i * 0.001));
  }
  const std::vector<wf::Panel> panels{{"p", "t", "y", {s}}};
  std::ostringstream os;
  wf::write_svg(os, "big", panels);
  const auto svg = wf::parse_xml(os.str());
  const auto pts = points_of(*svg.find_all("polyline").at(0));
  EXPECT_LT(pts.size(), 4U * 960U);
  double min_y = 1e9;
  for (const auto& p : pts) min_y = std::min(min_y, p.second);
  EXPECT_LT(min_y, 80.0);   // the 100.0 spikes survive decimation (drawn near the panel top)
}

TEST(waveform_svg, RejectsBadSeries) {
  std::ostringstream os;
  const std::vector<wf::Panel> mismatched{{"p", "t", "y", {wf::Series{"s", {1, 2}, {1}, {}, false}}}};
  EXPECT_THROW(wf::write_svg(os, "x", mismatched), std::invalid_argument);
  const std::vector<wf::Panel> nan{{"p", "t", "y", {wf::Series{"s", {1, 2}, {1, std::nan("")}, {}, false}}}};
  EXPECT_THROW(wf::write_svg(os, "x", nan), std::invalid_argument);
}

TEST(waveform_xml, CheckerRejectsMalformedDocuments) {
  EXPECT_NO_THROW(wf::parse_xml("<?xml version=\"1.0\"?><!-- c --><a x='1'><b/>t&amp;<c></c></a>\n"));
  EXPECT_THROW(wf::parse_xml("<a><b></a></b>"), wf::XmlError);
  EXPECT_THROW(wf::parse_xml("<a x=1/>"), wf::XmlError);
  EXPECT_THROW(wf::parse_xml("<a>&nbsp;</a>"), wf::XmlError);
  EXPECT_THROW(wf::parse_xml("<a/><b/>"), wf::XmlError);
  EXPECT_THROW(wf::parse_xml("<a x='1' x='2'/>"), wf::XmlError);
  EXPECT_THROW(wf::parse_xml("<a>"), wf::XmlError);
  EXPECT_THROW(wf::parse_xml("text"), wf::XmlError);
}
