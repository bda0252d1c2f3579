// Line splitting and number parsing for the QPS reader (see qps_lexer.hpp).
#include "qps_lexer.hpp"

#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace lcprelax::io {

QpsSection section_from_name(const std::string& k) {
  if (k == "NAME") return QpsSection::name;
  if (k == "OBJSENSE") return QpsSection::objsense;
  if (k == "ROWS") return QpsSection::rows;
  if (k == "COLUMNS") return QpsSection::columns;
  if (k == "RHS") return QpsSection::rhs;
  if (k == "RANGES") return QpsSection::ranges;
  if (k == "BOUNDS") return QpsSection::bounds;
  if (k == "QUADOBJ") return QpsSection::quadobj;
  if (k == "QMATRIX" || k == "QSECTION") return QpsSection::qmatrix;
  if (k == "ENDATA") return QpsSection::endata;
  return QpsSection::none;
}

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
}  // namespace

bool QpsLexer::next(std::vector<std::string>& fields) {
  while (lines_.next(text_)) {
    fields.clear();
    std::size_t i = 0;
    while (i < text_.size()) {
      while (i < text_.size() && is_space(text_[i])) ++i;
      const std::size_t start = i;
      while (i < text_.size() && !is_space(text_[i])) ++i;
      if (i > start) fields.emplace_back(text_, start, i - start);
    }
    if (fields.empty() || fields[0][0] == '*') continue;  // blank line or comment
    header_ = !is_space(text_[0]);
    return true;
  }
  return false;
}

void QpsLexer::fail_at(long line, const std::string& message) const {
  lines_.fail_at(line, message);
}

void QpsLexer::expect_fields(const std::vector<std::string>& fields, std::size_t lo, std::size_t hi,
                             const std::string& what) const {
  if (fields.size() >= lo && fields.size() <= hi) return;
  const std::string expected = lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi);
  fail(what + " has " + std::to_string(fields.size()) + " fields, expected " + expected);
}

double QpsLexer::number(const std::string& token) const {
  const char* begin = token.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0') fail(quote(token) + " is not a number");
  if (std::isnan(v)) fail("NaN value " + quote(token));
  // Overflow (1e999) gives ±inf, caught by finite_number() where infinity is not allowed.
  return v;
}

double QpsLexer::finite_number(const std::string& token) const {
  const double v = number(token);
  if (!std::isfinite(v)) fail("infinite value " + quote(token));
  return v;
}

std::string QpsLexer::format(double value) {
  std::ostringstream s;
  s.precision(12);
  s << value;
  return s.str();
}

}  // namespace lcprelax::io
