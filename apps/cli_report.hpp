#pragma once
// The human-readable output of every lcprelax subcommand (docs/cli.md, "Human output"): a
// brief report of aligned lines
//
//   status          solved
//   objective       -99.96
//   time            0.000105 s
//
// one quantity per line: its name, padded to the widest name of the report plus two
// spaces, then its value and, where it has one, its unit (SI: s, m, kg, m/s², ...). The
// first line is always `status`. Numbers are printed with 6 significant digits unless the
// caller asks for more; a non-finite number prints as `n/a` (the JSON output has null
// there). `--json` does not use this: it prints the one JSON object of cli_common.hpp.
#include <iosfwd>
#include <string>
#include <vector>

namespace lcprelax::cli {

/// `v` with `digits` significant digits (printf %g), or "n/a" when v is NaN or ±∞.
std::string format_number(double v, int digits = 6);

/// A brief report: lines added in order, printed aligned (see the header comment).
class BriefReport {
 public:
  /// A line `name  value unit` (unit may be empty).
  BriefReport& add(const std::string& name, const std::string& value, const std::string& unit = "");
  /// A line with a number formatted by format_number(value, digits).
  BriefReport& add(const std::string& name, double value, const std::string& unit = "", int digits = 6);
  /// A line with an integer count.
  BriefReport& add_count(const std::string& name, long long value, const std::string& unit = "");

  /// Prints every line to `out` (names padded to the widest name plus two spaces).
  void print(std::ostream& out) const;
  /// Prints to std::cout and flushes.
  void print() const;

 private:
  struct Line {
    std::string name, value, unit;
  };
  std::vector<Line> lines_;
};

}  // namespace lcprelax::cli
