// The brief human-readable report of the subcommands (cli_report.hpp).
#include "cli_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace lcprelax::cli {
namespace {

// Display width of a UTF-8 string: one column per code point (names such as "Δt" or
// "m/s²" must pad like their ASCII neighbours).
std::size_t columns(const std::string& s) {
  std::size_t n = 0;
  for (const char c : s)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  return n;
}

}  // namespace

std::string format_number(double v, int digits) {
  if (!std::isfinite(v)) return "n/a";
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", std::clamp(digits, 1, 17), v);
  return text;
}

BriefReport& BriefReport::add(const std::string& name, const std::string& value, const std::string& unit) {
  lines_.push_back({name, value, unit});
  return *this;
}

BriefReport& BriefReport::add(const std::string& name, double value, const std::string& unit, int digits) {
  // A unit after "n/a" would read as if the quantity had a value.
  return add(name, format_number(value, digits), std::isfinite(value) ? unit : "");
}

BriefReport& BriefReport::add_count(const std::string& name, long long value, const std::string& unit) {
  return add(name, std::to_string(value), unit);
}

void BriefReport::print(std::ostream& out) const {
  std::size_t width = 0;
  for (const Line& l : lines_) width = std::max(width, columns(l.name));
  for (const Line& l : lines_) {
    out << l.name << std::string(width + 2 - columns(l.name), ' ') << l.value;
    if (!l.unit.empty()) out << ' ' << l.unit;
    out << '\n';
  }
}

void BriefReport::print() const {
  print(std::cout);
  std::cout << std::flush;
}

}  // namespace lcprelax::cli
