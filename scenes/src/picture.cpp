// Pictures of a world with Cairo (scenes/picture.hpp).
#include <lcprelax/scenes/picture.hpp>
#include <lcprelax/core/atomic_file.hpp>
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

#ifndef LCPRELAX_HAS_CAIRO

void write_picture(const std::string&, const World&, const std::vector<Contact>&, const PictureOptions&) {
  throw std::runtime_error("built without Cairo");
}

std::string write_frame(const std::string&, int, const World&, const std::vector<Contact>&,
                        const PictureOptions&) {
  throw std::runtime_error("built without Cairo");
}

#else

namespace {

// World point of body vertex v: p = (x, y) + R(θ) v.
Vec2 world_point(const RigidBody& b, const Vec2& v) {
  const double c = std::cos(b.pose.z()), s = std::sin(b.pose.z());
  return Vec2(b.pose.x() + c * v.x() - s * v.y(), b.pose.y() + s * v.x() + c * v.y());
}

// Uniform map from the world box [xmin, xmax] × [ymin, ymax] onto width × height pixels.
struct View {
  double xmin = -1, xmax = 1, ymin = -1, ymax = 1;
  double scale = 1;  // px per m
  int width = 1, height = 1;
  Vec2 px(const Vec2& p) const { return Vec2((p.x() - xmin) * scale, (ymax - p.y()) * scale); }
};

View fit_view(const World& world, int width_px) {
  View v;
  bool any = false;
  auto extend = [&](const Vec2& p) {
    if (!any) {
      v.xmin = v.xmax = p.x();
      v.ymin = v.ymax = p.y();
      any = true;
    }
    v.xmin = std::min(v.xmin, p.x());
    v.xmax = std::max(v.xmax, p.x());
    v.ymin = std::min(v.ymin, p.y());
    v.ymax = std::max(v.ymax, p.y());
  };
  for (const RigidBody& b : world.bodies)
    for (const Vec2& p : b.shape.vertices) extend(world_point(b, p));
  for (const Segment& s : world.segments) {
    extend(s.a);
    extend(s.b);
  }
  if (!any) return View{-1, 1, -1, 1, width_px / 2.0, width_px, width_px};
  double w = v.xmax - v.xmin, h = v.ymax - v.ymin;
  double size = std::max(w, h);
  if (!(size > 0.0)) size = 1.0;
  auto grow = [](double& lo, double& hi, double to) {
    const double c = 0.5 * (lo + hi);
    lo = c - 0.5 * to;
    hi = c + 0.5 * to;
  };
  grow(v.xmin, v.xmax, w + 0.2 * size);  // 10% of the larger extent on each side
  grow(v.ymin, v.ymax, h + 0.2 * size);
  w = v.xmax - v.xmin;
  h = v.ymax - v.ymin;
  if (h < 0.25 * w) grow(v.ymin, v.ymax, h = 0.25 * w);
  if (w < 0.25 * h) grow(v.xmin, v.xmax, w = 0.25 * h);
  v.width = width_px;
  v.scale = width_px / w;
  v.height = std::max(1, static_cast<int>(std::lround(h * v.scale)));
  return v;
}

// Viridis-like colormap, t in [0, 1] (five control points of matplotlib's viridis).
void colormap(double t, double rgb[3]) {
  static const double k[5][3] = {{0.267, 0.005, 0.329}, {0.229, 0.322, 0.546}, {0.128, 0.567, 0.551},
                                 {0.369, 0.789, 0.383}, {0.993, 0.906, 0.144}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4.0;
  const int i = std::min(3, static_cast<int>(t));
  const double f = t - i;
  for (int c = 0; c < 3; ++c) rgb[c] = (1 - f) * k[i][c] + f * k[i + 1][c];
}

void check_input(const World& world, const std::vector<Contact>& contacts, const PictureOptions& o) {
  if (o.width_px < 16 || o.width_px > 16384)
    throw InputError("write_picture: width_px must be in [16, 16384], got " + std::to_string(o.width_px));
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const RigidBody& b = world.bodies[i];
    bool finite = b.pose.allFinite() && b.velocity.allFinite();
    for (const Vec2& v : b.shape.vertices) finite = finite && v.allFinite();
    if (!finite) throw InputError("write_picture: bodies[" + std::to_string(i) + "] is not finite");
  }
  for (std::size_t i = 0; i < world.segments.size(); ++i)
    if (!world.segments[i].a.allFinite() || !world.segments[i].b.allFinite())
      throw InputError("write_picture: segments[" + std::to_string(i) + "] is not finite");
  for (std::size_t i = 0; i < world.half_planes.size(); ++i)
    if (!world.half_planes[i].normal.allFinite() || !std::isfinite(world.half_planes[i].offset))
      throw InputError("write_picture: half_planes[" + std::to_string(i) + "] is not finite");
  for (std::size_t i = 0; i < contacts.size(); ++i)
    if (!contacts[i].point.allFinite() || !contacts[i].normal.allFinite())
      throw InputError("write_picture: contacts[" + std::to_string(i) + "] is not finite");
}

void draw(cairo_t* cr, const View& view, const World& world, const std::vector<Contact>& contacts,
          const PictureOptions& o) {
  const double lw = std::max(1.0, view.width / 800.0);  // line width (px)
  auto move = [&](const Vec2& p) { const Vec2 q = view.px(p); cairo_move_to(cr, q.x(), q.y()); };
  auto line = [&](const Vec2& p) { const Vec2 q = view.px(p); cairo_line_to(cr, q.x(), q.y()); };
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);

  // Half-planes: a band over the solid side {n·p < d}, long enough to cover the view.
  const Vec2 centre(0.5 * (view.xmin + view.xmax), 0.5 * (view.ymin + view.ymax));
  const double diag = std::hypot(view.xmax - view.xmin, view.ymax - view.ymin);
  for (const HalfPlane& h : world.half_planes) {
    const double len = h.normal.norm();
    if (!(len > 0.0)) continue;
    const Vec2 n = h.normal / len, t(-n.y(), n.x());
    const double dist = n.dot(centre) - h.offset / len;
    const Vec2 q = centre - dist * n;  // the view centre projected onto the boundary
    const double L = diag + std::abs(dist);
    move(q + L * t);
    line(q - L * t);
    line(q - L * t - 2 * L * n);
    line(q + L * t - 2 * L * n);
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, 0.82, 0.80, 0.76);
    cairo_fill(cr);
    move(q + L * t);
    line(q - L * t);
    cairo_set_source_rgb(cr, 0.35, 0.33, 0.30);
    cairo_set_line_width(cr, 1.5 * lw);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_set_line_width(cr, 2 * lw);
  for (const Segment& s : world.segments) {
    move(s.a);
    line(s.b);
    cairo_stroke(cr);
  }

  // Bodies, coloured by contact count or speed.
  const std::size_t nb = world.bodies.size();
  std::vector<double> value(nb, 0.0);
  if (o.color == PictureOptions::Color::contacts) {
    for (const Contact& c : contacts)
      for (int b : {c.body_a, c.body_b})
        if (b >= 0 && static_cast<std::size_t>(b) < nb) value[static_cast<std::size_t>(b)] += 1;
  } else {
    for (std::size_t i = 0; i < nb; ++i) value[i] = world.bodies[i].velocity.head<2>().norm();
  }
  double vmax = 0.0;
  for (std::size_t i = 0; i < nb; ++i)
    if (!world.bodies[i].is_static) vmax = std::max(vmax, value[i]);
  const double scale = vmax > 0.0 ? vmax : 1.0;
  cairo_set_line_width(cr, lw);
  for (std::size_t i = 0; i < nb; ++i) {
    const RigidBody& b = world.bodies[i];
    if (b.shape.vertices.empty()) continue;
    move(world_point(b, b.shape.vertices[0]));
    for (std::size_t k = 1; k < b.shape.vertices.size(); ++k) line(world_point(b, b.shape.vertices[k]));
    cairo_close_path(cr);
    double rgb[3] = {0.6, 0.6, 0.6};
    if (!b.is_static) colormap(value[i] / scale, rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_stroke(cr);
  }

  if (o.draw_contacts) {
    const double normal_len = 0.04 * (view.xmax - view.xmin);
    cairo_set_source_rgb(cr, 0.85, 0.1, 0.1);
    for (const Contact& c : contacts) {
      const Vec2 p = view.px(c.point);
      cairo_arc(cr, p.x(), p.y(), 2.5 * lw, 0, 6.283185307179586);
      cairo_fill(cr);
      move(c.point);
      line(c.point + normal_len * c.normal);
      cairo_stroke(cr);
    }
  }

  // Legend: title, then the colour scale as a bar from 0 to its maximum.
  const double fs = std::max(9.0, 14.0 * view.width / 1200.0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, fs);
  char range[128];
  if (o.color == PictureOptions::Color::contacts)
    std::snprintf(range, sizeof range, "contacts per body: 0 .. %g", vmax);
  else
    std::snprintf(range, sizeof range, "speed (m/s): 0 .. %.3g", vmax);
  const std::string text = (o.title.empty() ? "" : o.title + "   ") + range + "  ";
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_move_to(cr, fs, 1.5 * fs);
  cairo_show_text(cr, text.c_str());
  double x = 0, y = 0;
  cairo_get_current_point(cr, &x, &y);
  const int bar = static_cast<int>(8 * fs);
  for (int k = 0; k < bar; ++k) {
    double rgb[3];
    colormap(k / (bar - 1.0), rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_rectangle(cr, x + k, 0.6 * fs, 1.0, 0.9 * fs);
    cairo_fill(cr);
  }
}

// cairo_write_func_t appending to a std::string.
cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

void write_picture(const std::string& path, const World& world, const std::vector<Contact>& contacts,
                   const PictureOptions& options) {
  const detail::ImageFormat format = detail::image_format_of(path, "write_picture");
  check_input(world, contacts, options);
  const View view = fit_view(world, options.width_px);
  // Both formats are rendered into memory and the file is then replaced atomically
  // (core/atomic_file.hpp): a run killed while writing frames never leaves a truncated one.
  std::string bytes;
  std::unique_ptr<cairo_surface_t, detail::CairoSurfaceDeleter> surface(
      format == detail::ImageFormat::png ? cairo_image_surface_create(CAIRO_FORMAT_ARGB32, view.width, view.height)
                            : cairo_svg_surface_create_for_stream(append_bytes, &bytes, view.width, view.height));
  detail::check_cairo(cairo_surface_status(surface.get()), path, "write_picture");
#if CAIRO_VERSION >= CAIRO_VERSION_ENCODE(1, 16, 0)
  if (format == detail::ImageFormat::svg) cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
#endif
  {
    std::unique_ptr<cairo_t, detail::CairoContextDeleter> cr(cairo_create(surface.get()));
    draw(cr.get(), view, world, contacts, options);
    detail::check_cairo(cairo_status(cr.get()), path, "write_picture");
  }
  if (format == detail::ImageFormat::png) detail::check_cairo(cairo_surface_write_to_png_stream(surface.get(), append_bytes, &bytes), path, "write_picture");
  cairo_surface_finish(surface.get());  // flushes the SVG stream
  detail::check_cairo(cairo_surface_status(surface.get()), path, "write_picture");
  write_file_atomically(path, bytes);
}

std::string write_frame(const std::string& dir, int index, const World& world,
                        const std::vector<Contact>& contacts, const PictureOptions& options) {
  if (index < 0) throw InputError("write_frame: index must be >= 0, got " + std::to_string(index));
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("write_frame: cannot create " + dir + ": " + ec.message());
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.png", index);
  const std::string path = (std::filesystem::path(dir) / name).string();
  write_picture(path, world, contacts, options);
  return path;
}

#endif  // LCPRELAX_HAS_CAIRO

}  // namespace lcprelax
