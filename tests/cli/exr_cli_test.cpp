// .exr through the program: render writes it (float or --half, with the header's metadata),
// convert and diff read it, and scenes take it as a texture and as an environment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>

#include "raylane/image/exr.h"
#include "raylane/image/write_image.h"
#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::run_cli;
using testing::temp_dir;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_tiny_scene(const std::string& dir, const std::string& extra = "") {
  std::ofstream(dir + "/tiny.scn") << "screen 8 6\ncamera 0 0 5 1\nbrdf 0.5 0.5 0.5 0 0 0 1\n"
                                   << extra << "sphere 0 0 0 1\nlight 1 1 1\nsphere 0 3 3 1\n";
}

bool has_line(const std::vector<std::string>& lines, const std::string& line) {
  return std::find(lines.begin(), lines.end(), line) != lines.end();
}

TEST(CliExr, RenderWritesFloatAndHalfWithTheRunInTheHeader) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  auto r = run_cli("render tiny.scn --spp 2 -o a.exr -o a.pfm -q", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "a.exr\na.pfm\n");
  auto same = run_cli("diff a.exr a.pfm", dir);
  EXPECT_EQ(same.status, 0) << same.out;
  EXPECT_NE(same.out.find("rmse 0 "), std::string::npos) << same.out;
  auto info = probe_exr(read_file(dir + "/a.exr"));
  ASSERT_TRUE(info.ok()) << info.error();
  EXPECT_TRUE(has_line(info->metadata, "RAYLANE_SPP=2"));
  EXPECT_TRUE(has_line(info->metadata, "RAYLANE_MODE=path"));

  ASSERT_EQ(run_cli("render tiny.scn --spp 2 -o h.exr --half -q", dir).status, 0);
  EXPECT_LT(read_file(dir + "/h.exr").size(), read_file(dir + "/a.exr").size());
  EXPECT_EQ(run_cli("diff h.exr a.pfm --tol 0.01", dir).status, 0);

  auto warned = run_cli("render tiny.scn --spp 1 -o x.hdr --half", dir);
  EXPECT_EQ(warned.status, 0) << warned.out;
  EXPECT_NE(warned.out.find("--half does nothing"), std::string::npos) << warned.out;
}

TEST(CliExr, ConvertReadsAndWritesExr) {
  std::string dir = temp_dir();
  Image img(5, 3);
  for (std::size_t i = 0; i < img.rgb.size(); ++i)
    img.rgb[i] = 0.1f * float(i);
  ASSERT_TRUE(write_image(dir + "/in.pfm", img).ok());
  ASSERT_EQ(run_cli("convert in.pfm f.exr", dir).status, 0);
  ASSERT_EQ(run_cli("convert f.exr back.pfm", dir).status, 0);
  EXPECT_EQ(read_file(dir + "/back.pfm"), read_file(dir + "/in.pfm"));
  auto half = run_cli("convert in.pfm h.exr --half", dir);
  ASSERT_EQ(half.status, 0) << half.out;
  EXPECT_EQ(run_cli("diff h.exr in.pfm --tol 0.001", dir).status, 0);
  std::ofstream(dir + "/bad.exr") << "v/1\x01 not really";
  auto bad = run_cli("convert bad.exr out.pfm", dir);
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("cannot read 'bad.exr'"), std::string::npos) << bad.out;
}

TEST(CliExr, HelpNamesTheFormatAndHalf) {
  std::string dir = temp_dir();
  for (const char* cmd : {"render --help", "convert --help"}) {
    auto r = run_cli(cmd, dir);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find(".exr"), std::string::npos) << cmd << "\n" << r.out;
    EXPECT_NE(r.out.find("--half"), std::string::npos) << cmd << "\n" << r.out;
  }
}

TEST(CliExr, ScenesTakeExrTexturesAndEnvironments) {
  std::string dir = temp_dir();
  Image map(8, 4);
  for (std::size_t i = 0; i < map.rgb.size(); ++i)
    map.rgb[i] = 0.5f + 0.01f * float(i % 7);
  ASSERT_TRUE(write_image(dir + "/map.exr", map).ok());
  write_tiny_scene(dir, "texture map.exr\n");
  std::ofstream(dir + "/tiny.scn", std::ios::app) << "environment map.exr 1\n";
  auto r = run_cli("render tiny.scn --spp 1 -o t.pfm -q", dir);
  EXPECT_EQ(r.status, 0) << r.out;
  std::ofstream(dir + "/bad.exr") << std::string("v/1\x01\x02\0\0\0", 8);
  write_tiny_scene(dir, "texture bad.exr\n");
  auto bad = run_cli("render tiny.scn --spp 1 -o b.pfm -q", dir);
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("bad.exr"), std::string::npos) << bad.out;
}

// --aov with an EXR output: the AOVs are layers of the one file (albedo.R/G/B, depth.Z,
// normal.X/Y/Z), equal to the PFM siblings another output of the same run gets; an EXR-only
// render writes no siblings. The header names the run (seed, integrator, sampler).
TEST(CliExr, AovsAreLayersOfTheExrOutput) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  auto r = run_cli("render tiny.scn --spp 2 --aov albedo,normal,depth -o a.exr -o b.pfm -q", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "a.exr\nb.pfm\nb.albedo.pfm\nb.normal.pfm\nb.depth.pfm\n");
  const std::string exr = read_file(dir + "/a.exr");
  auto info = probe_exr(exr);
  ASSERT_TRUE(info) << info.error();
  EXPECT_TRUE(has_line(info->metadata, "RAYLANE_INTEGRATOR=mis")) << info->metadata.size();
  EXPECT_TRUE(has_line(info->metadata, "RAYLANE_SEED=0"));
  for (const char* aov : {"albedo", "normal", "depth"}) {
    SCOPED_TRACE(aov);
    auto layer = decode_exr_layer(exr, aov);
    ASSERT_TRUE(layer) << layer.error();
    auto sibling = read_image(dir + "/b." + aov + ".pfm");
    ASSERT_TRUE(sibling) << sibling.error();
    const std::size_t n = layer->channels.size(), pixels = sibling->rgb.size() / 3;
    ASSERT_EQ(layer->data.size(), pixels * n);
    for (std::size_t p = 0; p < pixels; ++p)
      for (std::size_t c = 0; c < n; ++c)
        ASSERT_EQ(layer->data[p * n + c], sibling->rgb[p * 3 + c]) << "pixel " << p;
  }
  EXPECT_EQ(decode_exr_layer(exr, "depth")->channels, std::vector<std::string>{"Z"});
  auto only = run_cli("render tiny.scn --spp 1 --aov depth -o c.exr -q", dir);
  ASSERT_EQ(only.status, 0) << only.out;
  EXPECT_EQ(only.out, "c.exr\n");
  EXPECT_FALSE(std::ifstream(dir + "/c.depth.pfm").good());
}

// convert from EXR to EXR keeps what render wrote beside the colour: every layer's channels
// bit for bit and every string attribute of the header; --half keeps them as halves. Nested
// layer names (LAYER.SUB.CHANNEL, as compositors write them) come through too.
TEST(CliExr, ConvertFromExrToExrKeepsTheLayersAndTheMetadata) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  auto r = run_cli("render tiny.scn --spp 2 --aov albedo,normal,depth,position -o a.exr -q", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  auto c = run_cli("convert a.exr b.exr", dir);
  ASSERT_EQ(c.status, 0) << c.out;
  EXPECT_EQ(c.out, "b.exr\n");
  const std::string a = read_file(dir + "/a.exr"), b = read_file(dir + "/b.exr");
  auto ia = probe_exr(a), ib = probe_exr(b);
  ASSERT_TRUE(ia && ib);
  EXPECT_EQ(ib->channels, ia->channels);
  EXPECT_EQ(ib->metadata, ia->metadata);
  EXPECT_TRUE(has_line(ib->metadata, "RAYLANE_SEED=0"));
  for (const std::string& layer : ia->layers) {
    SCOPED_TRACE(layer);
    auto la = decode_exr_layer(a, layer), lb = decode_exr_layer(b, layer);
    ASSERT_TRUE(la && lb);
    EXPECT_EQ(lb->channels, la->channels);
    ASSERT_EQ(lb->data.size(), la->data.size());
    EXPECT_EQ(std::memcmp(lb->data.data(), la->data.data(), la->data.size() * sizeof(float)), 0);
  }
  ASSERT_EQ(run_cli("convert a.exr h.exr --half", dir).status, 0);
  auto ih = probe_exr(read_file(dir + "/h.exr"));
  ASSERT_TRUE(ih);
  EXPECT_EQ(ih->channels, ia->channels);
  EXPECT_EQ(ih->metadata, ia->metadata);

  Image img(3, 2);
  ExrLayer nested{"diffuse.direct", {"R", "G", "B"}, std::vector<float>(18, 0.25f)};
  WriteOptions opts;
  opts.exr_layers = {nested};
  ASSERT_TRUE(write_image(dir + "/n.exr", img, opts).ok());
  ASSERT_EQ(run_cli("convert n.exr m.exr", dir).status, 0);
  auto got = decode_exr_layer(read_file(dir + "/m.exr"), "diffuse.direct");
  ASSERT_TRUE(got) << got.error();
  EXPECT_EQ(got->data, nested.data);
}

}  // namespace
}  // namespace raylane
