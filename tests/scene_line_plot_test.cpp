// scenes/line_plot.hpp: with Cairo, an SVG and a PNG of two series (one on log axes, with
// a non-positive point that is skipped) are written and look like what they are (the SVG
// has <svg and one path per series, the PNG starts with the PNG signature); bad input
// (extension, mismatched lengths, size) is an InputError whether or not Cairo is present.
#include <lcprelax/scenes/line_plot.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace lcprelax {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<LineSeries> two_series() {
  LineSeries a{"loss", {}, {}};
  LineSeries b{"gradient", {}, {}};
  for (int i = 0; i <= 20; ++i) {
    const double x = std::pow(10.0, -2.0 + 0.15 * i);
    a.x.push_back(x);
    a.y.push_back(1.0 + (x - 1.0) * (x - 1.0));
    b.x.push_back(x);
    b.y.push_back(i == 5 ? 0.0 : std::abs(2.0 * (x - 1.0)));  // one point not drawable on log y
  }
  b.markers = true;
  return {a, b};
}

TEST(LinePlot, WritesSvgAndPng) {
  if (!line_plot_available()) GTEST_SKIP() << "built without Cairo";
  const fs::path dir = fs::temp_directory_path() / ("lcprelax_line_plot_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  LinePlotOptions o;
  o.title = "landscape";
  o.x_label = "mu";
  o.y_label = "loss";
  o.log_x = o.log_y = true;
  write_line_plot((dir / "plot.svg").string(), two_series(), o);
  const std::string svg = slurp(dir / "plot.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_GT(svg.size(), 2000u);
  o.log_y = false;
  write_line_plot((dir / "plot.PNG").string(), two_series(), o);
  const std::string png = slurp(dir / "plot.PNG");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  write_line_plot((dir / "empty.svg").string(), {}, o);  // empty axes, no failure
  EXPECT_TRUE(fs::exists(dir / "empty.svg"));
  fs::remove_all(dir);
}

TEST(LinePlot, BadInputIsAnInputError) {
  EXPECT_THROW(write_line_plot("/tmp/x.bmp", two_series()), InputError);
  LineSeries bad{"bad", {1, 2, 3}, {1, 2}};
  EXPECT_THROW(write_line_plot("/tmp/x.svg", {bad}), InputError);
  LinePlotOptions o;
  o.width_px = 10;
  EXPECT_THROW(write_line_plot("/tmp/x.svg", two_series(), o), InputError);
}

}  // namespace
}  // namespace lcprelax
