// The human-readable verdict of a run (docs/sim.md): pass or fail, the failures, and per board
// the link, delivery and echo-check figures; and the client's figures the verdict takes for it.
#include <algorithm>
#include <sstream>
#include <vector>

#include "report.hpp"
#include "sim/xy/verdict.hpp"
#include "sim/text.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;

void report_client(BoardVerdict& v, const xy_client::ClientCounters& c, std::uint64_t frames_answered,
                   const std::vector<xy_client::Report>& reports) {
  v.commands = c.sent;
  v.echoes = c.answered;
  v.lost = c.timeouts;
  v.rejected = c.rejected;
  v.malformed = c.malformed;
  v.unexpected = c.resyncs;
  v.duplicates = c.late;
  v.delivery.submitted = c.commands;
  v.delivery.delivered = c.delivered;
  v.delivery.failed = c.failed;
  v.delivery.frames_answered = frames_answered;
  v.delivery.given_up = c.given_up;
  v.delivery.retransmissions = c.retransmissions;
  v.delivery.new_frames = c.new_frames;
  v.delivery.reports = reports;
}

std::string format_report(const sc::Scenario& s, const RunResult& r) {
  std::ostringstream o;
  o << "scenario " << s.name << ": " << (r.pass ? "PASS" : "FAIL") << "  (virtual " << fmt(static_cast<double>(r.vtime_us) / 1e6)
    << " s, wall " << fmt(r.wall_s) << " s, " << s.boards << " board(s), domain " << r.domain << ", " << r.bus_round_trips
    << " bus round trips)\n";
  for (const std::string& f : r.failures) o << "  FAIL " << f << '\n';
  const std::size_t shown = std::min<std::size_t>(r.boards.size(), 4);
  for (std::size_t i = 0; i < shown; ++i) {
    const BoardVerdict& b = r.boards[i];
    o << "  board " << b.board << ": commands " << b.commands << ", echoes " << b.echoes << ", gaps (lost echoes) "
      << b.lost << ", rejected " << b.rejected << ", malformed " << b.malformed << ", lost-step risks "
      << b.lost_step_risks << '\n';
    if (b.delivery.submitted > 0 || b.delivery.frames_taken > 0) {
      std::vector<std::int64_t> lat;
      for (const xy_client::Report& rep : b.delivery.reports) {
        if (xy_client::delivered(rep.outcome)) lat.push_back(rep.settled_us - rep.issued_us);
      }
      std::sort(lat.begin(), lat.end());
      o << "    delivery: " << b.delivery.submitted << " commands, " << b.delivery.delivered << " delivered, "
        << b.delivery.failed << " failed; " << b.delivery.new_frames << " frames, " << b.delivery.retransmissions
        << " retransmissions, " << b.delivery.given_up << " given up; the board took " << b.delivery.frames_taken
        << ", the client saw " << b.delivery.frames_answered << " answered; " << b.delivery.outcomes_checked
        << " outcomes checked";
      if (!lat.empty()) {
        o << "; confirmation " << fmt(static_cast<double>(lat[lat.size() / 2]) / 1000.0) << " ms median, "
          << fmt(static_cast<double>(lat.back()) / 1000.0) << " ms max";
      }
      o << '\n';
    }
    o << "    echo model: " << b.echoes_model_checked << " echoes checked, " << b.echo_disagreements
      << " disagreements; echoes from the board " << b.echoes_from_board << '\n';
    o << "    to board: frames " << b.to_board.frames << ", dropped " << b.to_board.dropped << ", corrupted "
      << b.to_board.corrupted << ", duplicated " << b.to_board.duplicated << ", reordered " << b.to_board.reordered
      << ", delayed " << b.to_board.delayed << ", cut " << b.to_board.cut << '\n';
    o << "    to PC:    frames " << b.to_pc.frames << ", dropped " << b.to_pc.dropped << ", corrupted " << b.to_pc.corrupted
      << ", duplicated " << b.to_pc.duplicated << ", reordered " << b.to_pc.reordered << ", delayed " << b.to_pc.delayed
      << ", cut " << b.to_pc.cut << '\n';
    if (!b.gaps.empty()) {
      o << "    gaps seen by the PC:";
      const std::size_t n = std::min<std::size_t>(b.gaps.size(), 12);
      for (std::size_t k = 0; k < n; ++k) o << ' ' << fmt(static_cast<double>(b.gaps[k].t_us) / 1e6) << "s:" << b.gaps[k].lost;
      if (b.gaps.size() > n) o << " ... (" << b.gaps.size() << " runs)";
      o << '\n';
    }
  }
  if (r.boards.size() > shown) o << "  ... and " << r.boards.size() - shown << " more boards\n";
  return o.str();
}


}  // namespace ap::sim::xy
