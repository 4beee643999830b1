// SVG line plots of a run (docs/sim.md): position and speed against time, one panel each,
// several traces per panel (like thesis Obr. 9-2, one curve per acceleration, and Obr. 9-3).
// Self-contained SVG 1.1 (no scripts, no external fonts or CSS); long series are decimated per
// pixel column keeping the min/max envelope. parse_xml() is the small well-formedness checker
// the tests run over the output.
#pragma once

#include <iosfwd>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ap::model::waveform {

struct Series {
  std::string label;
  std::vector<double> x, y;   // same length, x non-decreasing
  std::string color;          // empty: from the palette
  bool dashed = false;        // e.g. a requested value beside the actual one
};

struct Panel {
  std::string title, x_label, y_label;
  std::vector<Series> series;
};

struct SvgOptions {
  int width = 960;
  int panel_height = 300;
  std::size_t max_points = 4000;   // per series, after decimation (approximately)
};

// Throws std::invalid_argument on mismatched x/y lengths or non-finite values.
void write_svg(std::ostream& os, std::string_view title, std::span<const Panel> panels, SvgOptions opt = {});

struct MotionTrace {
  std::string label;                 // e.g. "X, a = 5 mm/s^2"
  std::vector<double> t_s;           // time [s]
  std::vector<double> pos_mm;        // position [mm]
  std::vector<double> speed_mm_s;    // speed [mm/s]
};
// Two panels: position [mm] and speed [mm/s] against time [s].
void write_motion_svg(std::ostream& os, std::string_view title, std::span<const MotionTrace> traces,
                      SvgOptions opt = {});

// ---- a small XML reader for checks --------------------------------------------------------------

class XmlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attrs;   // entity-decoded values
  std::vector<XmlElement> children;
  std::string text;                           // concatenated, entity-decoded character data

  [[nodiscard]] std::vector<const XmlElement*> find_all(std::string_view element) const;   // recursive
};

// Parses one document: optional <?xml ...?> prolog and comments, exactly one root element,
// balanced tags, quoted and unique attributes, known entities only. Throws XmlError.
XmlElement parse_xml(std::string_view text);

}  // namespace ap::model::waveform
