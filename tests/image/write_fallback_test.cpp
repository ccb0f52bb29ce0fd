// Nothing lost (docs/scene-language.md, "Output"): an image that cannot go where it was asked goes
// to a fallback file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "raylane/core/strings.h"
#include "raylane/image/write_fallback.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::temp_dir;

Image test_image() {
  Image img(5, 3);
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 5; ++x)
      img.set(x, y, {0.1f * x, 1e-3f * y, 123.456f + x * y});
  return img;
}

TEST(WriteFallback, WritesWhereAskedWhenItCan) {
  std::string dir = temp_dir();
  auto r = write_image_or_fallback(dir + "/ok.pfm", test_image(), {}, {dir + "/unused"});
  ASSERT_TRUE(r) << r.error();
  EXPECT_FALSE(r->is_fallback);
  EXPECT_EQ(r->path, dir + "/ok.pfm");
  EXPECT_TRUE(fs::exists(r->path));
}

// A folder that is a regular file cannot hold anything, even for root; the image lands in
// the first fallback folder that takes it, bit for bit, without replacing a file there.
TEST(WriteFallback, UnwritablePathGoesToTheFallbackLosslessly) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/plain") << "a file, not a folder";
  fs::create_directory(dir + "/rescue");
  Image img = test_image();
  auto r = write_image_or_fallback(dir + "/plain/render.png", img, {},
                                   {dir + "/no/such/folder", dir + "/rescue"});
  ASSERT_TRUE(r) << r.error();
  EXPECT_TRUE(r->is_fallback);
  EXPECT_FALSE(r->first_error.empty());
  EXPECT_EQ(fs::path(r->path).parent_path(), fs::path(dir + "/rescue"));
  EXPECT_EQ(fs::path(r->path).extension(), ".pfm");
  auto back = read_image(r->path);
  ASSERT_TRUE(back) << back.error();
  EXPECT_EQ(back->rgb, img.rgb);
  // A second rescue of the same name never replaces the first.
  auto again = write_image_or_fallback(dir + "/plain/render.png", img, {}, {dir + "/rescue"});
  ASSERT_TRUE(again) << again.error();
  EXPECT_NE(again->path, r->path);
  EXPECT_TRUE(fs::exists(r->path));
}

// A dangling link with the rescue file's name leads somewhere (here: a file the user keeps,
// once it is written); the rescue takes another name and writes nothing through the link.
TEST(WriteFallback, ARescueNeverWritesThroughALinkOfItsName) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/plain") << "x";
  fs::create_directory(dir + "/rescue");
  fs::create_symlink(dir + "/kept.film", fs::path(dir) / "rescue" /
                                             cat("raylane-rescue-render-", ::getpid(), "-0.pfm"));
  auto r = write_image_or_fallback(dir + "/plain/render.png", test_image(), {}, {dir + "/rescue"});
  ASSERT_TRUE(r) << r.error();
  EXPECT_TRUE(r->is_fallback);
  EXPECT_FALSE(fs::exists(dir + "/kept.film"));
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(r->path)));
}

TEST(WriteFallback, ErrorOnlyWhenNothingTakesTheImage) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/plain") << "x";
  auto r = write_image_or_fallback(dir + "/plain/a.hdr", test_image(), {}, {dir + "/plain"});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("could not be written anywhere"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find(dir + "/plain/a.hdr"), std::string::npos) << r.error();
}

}  // namespace
}  // namespace raylane
