// Hostile input through the program (docs/design.md, "Memory" and "Images in"): a film or a texture
// that does not fit in memory is refused before it is allocated, naming what and how much (never
// std::bad_alloc's abort); a decompression bomb is refused by the image memory budget, which
// --image-memory raises; `info` reads image headers only; an output through a symbolic link keeps
// the link.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "raylane/core/alloc_budget.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_image.h"
#include "support/cli_run.h"
#include "support/hostile_files.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;
using testing::run_cli_within;
using testing::temp_dir;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

const char* kScene = "camera 0 0 5 1\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\n";

// The sanitizers reserve terabytes of address space for their shadow memory, so `ulimit -v`
// cannot stand for a small machine there (AllocBudget::enforced() is false in those builds).
bool address_space_limits_work() {
  return AllocBudget::enforced();
}

TEST(CliHostile, AFilmAtThePixelLimitThatDoesNotFitIsRefusedBeforeRendering) {
  if (!address_space_limits_work()) GTEST_SKIP() << "sanitizer build";
  std::string dir = temp_dir();
  write_file(dir + "/big.scn", std::string("screen 16384 16384\n") + kScene);
  auto path = run_cli_within("render big.scn --spp 1 --threads 2 -o big.hdr", dir,
                             2 << 20);  // 2 GiB
  EXPECT_EQ(path.status, 2) << path.out;
  EXPECT_NE(path.out.find("a 16384x16384 render (its film and images, with 2 threads) needs "
                          "15.1 GiB; this process can have"),
            std::string::npos)
      << path.out;
  EXPECT_NE(path.out.find("(ulimit -v); nothing rendered"), std::string::npos) << path.out;
  auto normal = run_cli_within("render big.scn --mode normal --threads 2 -o big.hdr", dir, 2 << 20);
  EXPECT_EQ(normal.status, 2) << normal.out;
  EXPECT_NE(normal.out.find("the 16384x16384 image (2 threads) needs 9.1 GiB"), std::string::npos)
      << normal.out;
  EXPECT_FALSE(fs::exists(dir + "/big.hdr"));
}

// What writing a render's files takes is counted before it starts: under any address-space
// limit a render is either refused before rendering, writing nothing, or it writes every file
// — never rendered and then lost to "out of memory" (the series, EXR layers, AOV siblings and
// 8-bit conversions all held at once did that between 276 and 330 MiB here). The sweep
// crosses the boundary, so both outcomes are seen.
TEST(CliHostile, UnderAnyMemoryLimitARenderIsRefusedOrWritesEveryFile) {
  if (!address_space_limits_work()) GTEST_SKIP() << "sanitizer build";
  std::string dir = temp_dir();
  write_file(dir + "/k.scn", std::string("screen 1024 1024\n") + kScene);
  const char* files[] = {"a.exr",   "a.png",   "a.hdr",   "a.albedo.pfm",   "a.position.pfm",
                         "a.1.exr", "a.1.png", "a.1.hdr", "a.1.normal.pfm", "a.1.depth.pfm"};
  int refused = 0, written = 0;
  for (uint64_t mib = 272; mib <= 400; mib += 8) {
    SCOPED_TRACE(cat(mib, " MiB"));
    for (const char* f : files)
      fs::remove(dir + "/" + f);
    auto r = run_cli_within(
        "render k.scn --spp 2 -q --aov albedo,normal,depth,position "
        "--save-at 1 -o a.exr -o a.png -o a.hdr --threads 2",
        dir, mib << 10);
    if (r.status == 2) {
      ++refused;
      EXPECT_NE(r.out.find("; nothing rendered"), std::string::npos) << r.out;
      for (const char* f : files)
        EXPECT_FALSE(fs::exists(dir + "/" + f)) << f;
      continue;
    }
    ++written;
    EXPECT_EQ(r.status, 0) << r.out;
    for (const char* f : files)
      EXPECT_TRUE(fs::exists(dir + "/" + f)) << f << "\n" << r.out;
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(written, 0);
}

// A --region's film, AOVs, --save-at series and outputs are the region's size: a 4x4 corner
// of a screen whose whole film would need 12 GiB renders within 512 MiB of address space, in
// every mode, and its files are 4x4.
TEST(CliHostile, ARegionTakesTheRegionsMemoryNotTheScreens) {
  if (!address_space_limits_work()) GTEST_SKIP() << "sanitizer build";
  std::string dir = temp_dir();
  write_file(dir + "/big.scn", std::string("screen 16384 16384\n") + kScene);
  auto within = [&](const std::string& args) {
    return run_cli_within("render big.scn " + args + " --region 8190,8190,8194,8194", dir,
                          512 << 10);
  };
  auto path = within(
      "--spp 4 --aov albedo,normal --save-at 1,2 --checkpoint c.film -o r.hdr "
      "-o r.exr");
  ASSERT_EQ(path.status, 0) << path.out;
  for (const char* file : {"r.hdr", "r.exr", "r.1.hdr", "r.2.exr", "r.albedo.pfm"}) {
    auto image = read_image(dir + "/" + file);
    ASSERT_TRUE(image.ok()) << file << ": " << image.error();
    EXPECT_EQ(image->width, 4u) << file;
    EXPECT_EQ(image->height, 4u) << file;
  }
  EXPECT_LT(fs::file_size(dir + "/c.film"), 4096u);  // 16 pixels' sums, not 2^28
  auto resumed = within("--spp 6 --aov albedo,normal --resume c.film -o s.hdr");
  EXPECT_EQ(resumed.status, 0) << resumed.out;
  for (const char* mode : {"normal", "lit", "depth"}) {
    auto view = within(std::string("-o v.png --mode ") + mode);
    EXPECT_EQ(view.status, 0) << mode << "\n" << view.out;
  }
}

// A texture whose pixels fit the budget once raised, but not the process: reading it peaks at
// 704 MiB (stb's samples and the 8-bit texels), more than 700 MiB of address space hold.
TEST(CliHostile, ATextureThatDoesNotFitInMemoryIsAnErrorNotAnAbort) {
  if (!address_space_limits_work()) GTEST_SKIP() << "sanitizer build";
  std::string dir = temp_dir();
  write_file(dir + "/bomb.png", testing::png_zero_bomb(8192, 8192));
  write_file(dir + "/t.scn", std::string(kScene) + "texture bomb.png\n");
  auto r = run_cli_within("render t.scn --spp 1 --image-memory 4096 -o t.hdr", dir, 700 << 10);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("decoding its 8192x8192 pixels needs 704.1 MiB; this process can have"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(dir + "/t.hdr"));
  // `info` reads the header only: the bomb's size, with nothing decoded, in the same memory,
  // and the warning that render refuses it, with exit status 2.
  auto info = run_cli_within("info t.scn", dir, 700 << 10);
  EXPECT_EQ(info.status, 2) << info.out;
  EXPECT_NE(info.out.find("texture      8192 x 8192, keeps 256.0 MiB, reading peaks at 704.1 MiB: "
                          "'bomb.png'"),
            std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("warning: render refuses it: reading its 8192x8192 pixels takes"),
            std::string::npos)
      << info.out;
}

TEST(CliHostile, APngBombIsRefusedUnlessTheBudgetIsRaised) {
  std::string dir = temp_dir();
  write_file(dir + "/bomb.png", testing::png_zero_bomb(8192, 8192));
  write_file(dir + "/t.scn", std::string(kScene) + "texture bomb.png\n");
  auto r = run_cli("render t.scn --spp 1 -o t.hdr", dir);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("t.scn:4:9: cannot use texture 'bomb.png': "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reading its 8192x8192 pixels takes 704.1 MiB from a file of "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("--image-memory 705 reads them"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/t.hdr"));
  auto bad = run_cli("render t.scn --image-memory lots", dir);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--image-memory"), std::string::npos) << bad.out;
}

// -o through a link writes the link's target (atomically, beside it) and keeps the link; a link
// to a device is written in place, and its write error reported.
TEST(CliHostile, AnOutputThroughASymbolicLinkKeepsTheLink) {
  std::string dir = temp_dir();
  write_file(dir + "/s.scn", std::string("screen 8 6\n") + kScene);
  fs::create_directory(dir + "/renders");
  write_file(dir + "/renders/full.hdr", "old");
  fs::create_symlink("renders/full.hdr", dir + "/full.hdr");
  fs::create_symlink("renders/new.pfm", dir + "/dangling.pfm");
  auto r = run_cli("render s.scn --mode normal -o full.hdr -o dangling.pfm -q", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(fs::is_symlink(dir + "/full.hdr"));
  EXPECT_TRUE(fs::is_symlink(dir + "/dangling.pfm"));
  EXPECT_EQ(read_file(dir + "/renders/full.hdr").rfind("#?RADIANCE", 0), 0u);
  EXPECT_EQ(read_file(dir + "/renders/new.pfm").rfind("PF\n8 6", 0), 0u);
  for (const auto& e : fs::directory_iterator(dir + "/renders"))  // no temporary left behind
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  if (!fs::exists("/dev/full")) return;
  fs::create_symlink("/dev/full", dir + "/full.pfm");
  auto full = run_cli("render s.scn --mode normal -o full.pfm -q", dir);
  EXPECT_EQ(full.status, 1) << full.out;
  EXPECT_NE(full.out.find("No space left on device"), std::string::npos) << full.out;
  EXPECT_TRUE(fs::is_symlink(dir + "/full.pfm"));
}

}  // namespace
}  // namespace raylane
