// Line plots with Cairo (scenes/line_plot.hpp).
#include <lcprelax/scenes/line_plot.hpp>
#include <lcprelax/core/errors.hpp>

#include "cairo_output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#ifdef LCPRELAX_HAS_CAIRO
#include <cairo-svg.h>
#include <cairo.h>
#endif

namespace lcprelax {

namespace {

void validate(const std::string& path, const std::vector<LineSeries>& series, const LinePlotOptions& o) {
  detail::image_format_of(path, "write_line_plot");
  if (o.width_px < 64 || o.width_px > 16384 || o.height_px < 64 || o.height_px > 16384)
    throw InputError("write_line_plot: width and height must be in [64, 16384] pixels");
  for (std::size_t i = 0; i < series.size(); ++i)
    if (series[i].x.size() != series[i].y.size())
      throw InputError("write_line_plot: series " + std::to_string(i) + " ('" + series[i].name +
                       "') has x and y of different lengths");
}

}  // namespace

#ifndef LCPRELAX_HAS_CAIRO

bool line_plot_available() { return false; }

void write_line_plot(const std::string& path, const std::vector<LineSeries>& series, const LinePlotOptions& options) {
  validate(path, series, options);
  throw std::runtime_error("built without Cairo");
}

#else

bool line_plot_available() { return true; }

namespace {

// One axis: data range [lo, hi] (in log10 units on a log axis) onto pixels [p0, p1].
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;
  double p0 = 0.0, p1 = 1.0;
  bool drawable(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
  double t(double v) const { return log ? std::log10(v) : v; }
  double px(double v) const { return p0 + (t(v) - lo) / (hi - lo) * (p1 - p0); }
};

void fit(Axis& a, const std::vector<double>& values, double fixed_lo, double fixed_hi) {
  if (fixed_lo < fixed_hi && std::isfinite(fixed_lo) && std::isfinite(fixed_hi) && (!a.log || fixed_lo > 0.0)) {
    a.lo = a.t(fixed_lo);
    a.hi = a.t(fixed_hi);
    return;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values)
    if (a.drawable(v)) {
      lo = std::min(lo, a.t(v));
      hi = std::max(hi, a.t(v));
    }
  if (!(lo <= hi)) {
    a.lo = 0.0;
    a.hi = 1.0;
    return;
  }
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(lo))) {
    a.lo = lo - 1.0;
    a.hi = hi + 1.0;
  } else if (a.log && hi - lo < 6.0) {
    a.lo = std::floor(lo);
    a.hi = std::max(std::ceil(hi), a.lo + 1.0);
  } else {
    const double pad = 0.04 * (hi - lo);
    a.lo = lo - pad;
    a.hi = hi + pad;
  }
}

// Tick positions in data units (not log units).
std::vector<double> ticks(const Axis& a) {
  std::vector<double> out;
  if (a.log) {
    const double span = a.hi - a.lo;
    const int step = std::max(1, static_cast<int>(std::ceil(span / 8.0)));
    for (int e = static_cast<int>(std::ceil(a.lo - 1e-9)); e <= static_cast<int>(std::floor(a.hi + 1e-9)); e += step) {
      out.push_back(std::pow(10.0, e));
      if (span <= 2.0)
        for (double m : {2.0, 5.0})
          if (std::log10(m) + e <= a.hi + 1e-9) out.push_back(m * std::pow(10.0, e));
    }
    return out;
  }
  const double raw = (a.hi - a.lo) / 6.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  for (double v = std::ceil(a.lo / step) * step; v <= a.hi + 1e-9 * step; v += step)
    out.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  return out;
}

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

const double kPalette[10][3] = {{0.12, 0.47, 0.71}, {1.00, 0.50, 0.05}, {0.17, 0.63, 0.17}, {0.84, 0.15, 0.16},
                                {0.58, 0.40, 0.74}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}, {0.50, 0.50, 0.50},
                                {0.74, 0.74, 0.13}, {0.09, 0.75, 0.81}};

void text_at(cairo_t* cr, double x, double y, const std::string& s, double ax, double ay, bool vertical = false) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_save(cr);
  cairo_translate(cr, x, y);
  if (vertical) cairo_rotate(cr, -M_PI / 2);
  cairo_move_to(cr, -ax * e.width - e.x_bearing, -ay * e.height - e.y_bearing);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

void draw(cairo_t* cr, const std::vector<LineSeries>& series, const LinePlotOptions& o) {
  const double W = o.width_px, H = o.height_px, fs = std::max(10.0, H / 45.0);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, fs);
  Axis ax, ay;
  ax.log = o.log_x;
  ay.log = o.log_y;
  std::vector<double> xs, ys;
  for (const LineSeries& s : series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (ax.drawable(s.x[i]) && ay.drawable(s.y[i])) {
        xs.push_back(s.x[i]);
        ys.push_back(s.y[i]);
      }
  fit(ax, xs, o.x_min, o.x_max);
  fit(ay, ys, o.y_min, o.y_max);
  const double left = 5.5 * fs, right = W - 1.5 * fs, top = (o.title.empty() ? 1.5 : 3.0) * fs, bottom = H - 4.0 * fs;
  ax.p0 = left;
  ax.p1 = right;
  ay.p0 = bottom;
  ay.p1 = top;
  // Grid, ticks and numbers.
  cairo_set_line_width(cr, 1.0);
  for (double v : ticks(ax)) {
    const double p = ax.px(v);
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, p, top);
    cairo_line_to(cr, p, bottom);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text_at(cr, p, bottom + 0.5 * fs, label(v), 0.5, 0.0);
  }
  for (double v : ticks(ay)) {
    const double p = ay.px(v);
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, left, p);
    cairo_line_to(cr, right, p);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text_at(cr, left - 0.4 * fs, p, label(v), 1.0, 0.5);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, left, top, right - left, bottom - top);
  cairo_stroke(cr);
  if (!o.x_label.empty()) text_at(cr, 0.5 * (left + right), H - 0.4 * fs, o.x_label, 0.5, 1.0);
  if (!o.y_label.empty()) text_at(cr, 0.4 * fs, 0.5 * (top + bottom), o.y_label, 0.5, 0.0, true);
  if (!o.title.empty()) text_at(cr, 0.5 * (left + right), 0.6 * fs, o.title, 0.5, 0.0);
  // Series, clipped to the plot area.
  cairo_save(cr);
  cairo_rectangle(cr, left, top, right - left, bottom - top);
  cairo_clip(cr);
  cairo_set_line_width(cr, 2.0);
  for (std::size_t k = 0; k < series.size(); ++k) {
    const LineSeries& s = series[k];
    const double* c = kPalette[k % 10];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    const double dash[] = {6.0, 4.0};
    cairo_set_dash(cr, dash, s.dashed ? 2 : 0, 0.0);
    bool pen = false;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!ax.drawable(s.x[i]) || !ay.drawable(s.y[i])) {
        pen = false;
        continue;
      }
      const double px = ax.px(s.x[i]), py = ay.px(s.y[i]);
      if (s.lines) {
        if (pen) cairo_line_to(cr, px, py);
        else cairo_move_to(cr, px, py);
        pen = true;
      }
    }
    if (s.lines) cairo_stroke(cr);
    cairo_set_dash(cr, dash, 0, 0.0);
    if (s.markers)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (ax.drawable(s.x[i]) && ay.drawable(s.y[i])) {
          cairo_arc(cr, ax.px(s.x[i]), ay.px(s.y[i]), 3.0, 0.0, 2 * M_PI);
          cairo_fill(cr);
        }
  }
  cairo_restore(cr);
  // Legend (top right, inside the plot area).
  double y = top + 0.8 * fs;
  double wmax = 0.0;
  for (const LineSeries& s : series) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.name.c_str(), &e);
    wmax = std::max(wmax, e.x_advance);
  }
  const double x0 = right - wmax - 4.0 * fs;
  for (std::size_t k = 0; k < series.size(); ++k) {
    if (series[k].name.empty()) continue;
    const double* c = kPalette[k % 10];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_move_to(cr, x0, y);
    cairo_line_to(cr, x0 + 2.0 * fs, y);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text_at(cr, x0 + 2.5 * fs, y, series[k].name, 0.0, 0.5);
    y += 1.3 * fs;
  }
}

}  // namespace

void write_line_plot(const std::string& path, const std::vector<LineSeries>& series, const LinePlotOptions& options) {
  validate(path, series, options);
  const detail::ImageFormat format = detail::image_format_of(path, "write_line_plot");
  std::unique_ptr<cairo_surface_t, detail::CairoSurfaceDeleter> surface(
      format == detail::ImageFormat::png ? cairo_image_surface_create(CAIRO_FORMAT_ARGB32, options.width_px, options.height_px)
                            : cairo_svg_surface_create(path.c_str(), options.width_px, options.height_px));
  detail::check_cairo(cairo_surface_status(surface.get()), path, "write_line_plot");
  if (format == detail::ImageFormat::svg) cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
  {
    std::unique_ptr<cairo_t, detail::CairoContextDeleter> cr(cairo_create(surface.get()));
    draw(cr.get(), series, options);
    detail::check_cairo(cairo_status(cr.get()), path, "write_line_plot");
  }
  if (format == detail::ImageFormat::png) detail::check_cairo(cairo_surface_write_to_png(surface.get(), path.c_str()), path, "write_line_plot");
  cairo_surface_finish(surface.get());
  detail::check_cairo(cairo_surface_status(surface.get()), path, "write_line_plot");
}

#endif

}  // namespace lcprelax
