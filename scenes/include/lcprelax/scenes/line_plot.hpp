#pragma once
// A small line plot (PNG or SVG) drawn with Cairo: several named series of (x, y) points,
// optional logarithmic x and/or y axes, axis labels, ticks with numbers, a grid, a legend
// and a title. For loss landscapes, error against epochs or run time, and the like.
// Optional at build time (LCPRELAX_WITH_CAIRO → LCPRELAX_HAS_CAIRO): without Cairo,
// line_plot_available() is false and write_line_plot() throws std::runtime_error("built
// without Cairo") after validating its input.
//
// Conventions:
// - The format follows the file extension: ".png" or ".svg" (case-insensitive); anything
//   else is an InputError.
// - Points with a non-finite coordinate, or a coordinate ≤ 0 on a log axis, are skipped and
//   break the line there (so gaps are visible, nothing is invented).
// - The axis ranges fit all drawable points (plus 4% padding on linear axes; log axes are
//   widened to whole decades when they span fewer than 6); a degenerate range (one value)
//   is widened to ±1 (linear) or a decade either side (log). No drawable point at all
//   gives the range [0, 1] (linear) or [1, 10] (log) and empty axes.
// - Series are coloured from a fixed 10-colour palette in order; each series can draw
//   lines, markers or both. A series with an empty name is left out of the legend.
#include <string>
#include <vector>

namespace lcprelax {

struct LineSeries {
  std::string name;        ///< legend entry (empty: not in the legend)
  std::vector<double> x;   ///< same length as y
  std::vector<double> y;
  bool lines = true;       ///< connect consecutive drawable points
  bool markers = false;    ///< draw a dot at every drawable point
  bool dashed = false;
};

struct LinePlotOptions {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_x = false;
  bool log_y = false;
  int width_px = 900;      ///< 64..16384
  int height_px = 600;     ///< 64..16384
  /// Optional fixed ranges (used when lo < hi and both finite; for log axes both > 0).
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;
};

/// True when lcprelax was built with Cairo (pictures can be written).
bool line_plot_available();

/// Writes the plot to `path` (.png or .svg). InputError for a bad extension, series whose
/// x and y differ in length, or sizes out of range; std::runtime_error if the file cannot
/// be written or without Cairo.
void write_line_plot(const std::string& path, const std::vector<LineSeries>& series,
                     const LinePlotOptions& options = {});

}  // namespace lcprelax
