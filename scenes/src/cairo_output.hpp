#pragma once
// Internal helpers shared by the Cairo writers (picture.cpp, line_plot.cpp): the output
// format from the file name, owning pointers for Cairo objects and status checks. Messages
// start with the writer's name (`who`) and the path.
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>
#include <string>

#ifdef LCPRELAX_HAS_CAIRO
#include <cairo.h>
#endif

namespace lcprelax::detail {

enum class ImageFormat { png, svg };

/// PNG or SVG from the extension (case-insensitive); InputError for any other name.
inline ImageFormat image_format_of(const std::string& path, const char* who) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".svg") return ImageFormat::svg;
  throw InputError(std::string(who) + ": " + path + ": the file name must end in .svg or .png");
}

#ifdef LCPRELAX_HAS_CAIRO
struct CairoSurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct CairoContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

/// Throws std::runtime_error "<who>: <path>: <Cairo's message>" unless status is success.
inline void check_cairo(cairo_status_t status, const std::string& path, const char* who) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string(who) + ": " + path + ": " + cairo_status_to_string(status));
}
#endif

}  // namespace lcprelax::detail
