// Pictures: write_picture writes a valid PNG (8-byte signature, IHDR width) and an SVG,
// write_frame names frames frame_NNNNNN.png, bad paths and non-finite worlds are
// InputErrors; without Cairo every call throws "built without Cairo".
#include <gtest/gtest.h>

#include <lcprelax/scenes/picture.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#ifdef LCPRELAX_HAS_CAIRO
// Cairo's text drawing initializes fontconfig, whose global caches are never freed: not a
// leak of ours. LeakSanitizer reads this hook in LCPRELAX_SANITIZE builds.
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
#endif

namespace lcprelax {
namespace {

const std::string kDir = std::string(LCPRELAX_TEST_DATA_DIR) + "/scenes/";

// Contacts of the stack of three boxes: two corners on the ground and between each pair.
std::vector<Contact> stack_contacts() {
  std::vector<Contact> cs;
  for (int level = 0; level < 3; ++level)
    for (double x : {-0.5, 0.5}) {
      Contact c;
      c.body_a = level;
      c.body_b = level == 0 ? -1 : level - 1;
      c.static_kind = level == 0 ? Contact::StaticKind::half_plane : Contact::StaticKind::none;
      c.static_index = level == 0 ? 0 : -1;
      c.point = Vec2(x, level);
      c.normal = Vec2(0, 1);
      cs.push_back(c);
    }
  return cs;
}

#ifdef LCPRELAX_HAS_CAIRO

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string out_dir() {
  const std::string dir = testing::TempDir() + "/lcprelax_picture_test";
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(ScenePicture, WritesPngWithSignatureAndWidth) {
  const Scene s = load_scene(kDir + "box_stack.json");
  PictureOptions o;
  o.draw_contacts = true;
  o.width_px = 640;
  o.title = "box_stack";
  const std::string path = out_dir() + "/stack.png";
  write_picture(path, s.world, stack_contacts(), o);
  const std::string png = read_all(path);
  ASSERT_GT(png.size(), 100u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: length(4) "IHDR" width(4, big-endian) height(4).
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  const auto byte = [&](std::size_t i) { return static_cast<unsigned>(static_cast<unsigned char>(png[i])); };
  EXPECT_EQ((byte(16) << 24) | (byte(17) << 16) | (byte(18) << 8) | byte(19), 640u);
  const unsigned height = (byte(20) << 24) | (byte(21) << 16) | (byte(22) << 8) | byte(23);
  EXPECT_GE(height, 640u);  // a tall stack: height ≥ width, at most 4× the width
  EXPECT_LE(height, 4 * 640u);
}

TEST(ScenePicture, WritesSvgColouredBySpeed) {
  Scene s = load_scene(kDir + "triangle_on_incline.json");
  s.world.bodies[0].velocity = Vec3(-1, -0.5, 0);
  PictureOptions o;
  o.color = PictureOptions::Color::speed;
  const std::string path = out_dir() + "/incline.SVG";
  write_picture(path, s.world, {}, o);
  const std::string svg = read_all(path);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(ScenePicture, EmptyWorldAndFrames) {
  World empty;
  const std::string dir = out_dir() + "/frames";
  std::filesystem::remove_all(dir);
  const std::string path = write_frame(dir, 123, empty, {}, PictureOptions{});
  EXPECT_EQ(std::filesystem::path(path).filename().string(), "frame_000123.png");
  EXPECT_EQ(read_all(path).substr(1, 3), "PNG");
  EXPECT_THROW(write_frame(dir, -1, empty, {}, PictureOptions{}), InputError);
}

TEST(ScenePicture, BadInput) {
  const Scene s = load_scene(kDir + "box_on_ground.json");
  EXPECT_THROW(write_picture(out_dir() + "/x.jpg", s.world, {}, PictureOptions{}), InputError);
  EXPECT_THROW(write_picture(out_dir() + "/x", s.world, {}, PictureOptions{}), InputError);
  PictureOptions narrow;
  narrow.width_px = 4;
  EXPECT_THROW(write_picture(out_dir() + "/x.png", s.world, {}, narrow), InputError);
  World w = s.world;
  w.bodies[0].pose.x() = NAN;
  EXPECT_THROW(write_picture(out_dir() + "/x.png", w, {}, PictureOptions{}), InputError);
  EXPECT_THROW(write_picture(out_dir() + "/no_such_dir/x.png", s.world, {}, PictureOptions{}), std::runtime_error);
}

#else

TEST(ScenePicture, ThrowsWithoutCairo) {
  const Scene s = load_scene(kDir + "box_on_ground.json");
  try {
    write_picture("x.png", s.world, stack_contacts(), PictureOptions{});
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "built without Cairo");
  }
  EXPECT_THROW(write_frame(".", 0, s.world, {}, PictureOptions{}), std::runtime_error);
}

#endif

}  // namespace
}  // namespace lcprelax
