// Inputs are read, never eaten (README.md, "Using it"): an output that is an input or another
// output is a usage error before any work, compared by file identity; a path that is no regular
// file (FIFO, directory) is an error naming it, never a hang.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;
using testing::source_path;
using testing::temp_dir;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

const char* kScene = "camera 0 0 5 1\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\n";

// Each case must fail with status 2, name the collision, and leave the input as it was.
void expect_refused(const std::string& args, const std::string& dir, const std::string& input) {
  std::string before = read_file(dir + "/" + input);
  auto r = run_cli(args, dir);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
  EXPECT_NE(r.out.find("would destroy an input"), std::string::npos) << args << "\n" << r.out;
  EXPECT_EQ(read_file(dir + "/" + input), before) << args;
}

// Scenes and meshes named like images here, so that the output's format is fine and only the
// collision stops the run.
TEST(CliInputs, AnOutputThatIsAnInputIsRefusedBeforeAnyWork) {
  std::string dir = temp_dir();
  fs::create_directory(dir + "/sub");
  write_file(dir + "/scene.hdr", kScene);  // a scene file with an image's name
  write_file(dir + "/s.scn", kScene);
  fs::create_symlink("s.scn", dir + "/link.hdr");
  fs::copy_file(source_path("scenes/letterX.ply"), dir + "/x.png");
  write_file(dir + "/m.scn", std::string(kScene) + "mesh x.png 0 0 0 1\n");
  expect_refused("render scene.hdr --spp 1", dir, "scene.hdr");  // the default output
  expect_refused("render scene.hdr --spp 1 -o ./sub/../scene.hdr", dir, "scene.hdr");
  expect_refused("render s.scn --spp 1 -o link.hdr", dir, "s.scn");     // through a link
  expect_refused("render m.scn --mode normal -o x.png", dir, "x.png");  // a mesh it reads
  expect_refused("render s.scn --spp 1 --checkpoint link.hdr", dir, "s.scn");
  fs::copy_file(source_path("scenes/letterX.ply"), dir + "/x.ply");
  expect_refused("trace x.ply x.ply -o x.ply", dir, "x.ply");
  write_file(dir + "/img.pfm", "");
  ASSERT_EQ(run_cli("render s.scn --mode normal -o img.pfm", dir).status, 0);
  expect_refused("convert img.pfm img.pfm", dir, "img.pfm");
  expect_refused("convert img.pfm ./img.pfm", dir, "img.pfm");
}

TEST(CliInputs, TwoOutputsThatAreOneFileAreRefused) {
  std::string dir = temp_dir();
  write_file(dir + "/s.scn", kScene);
  auto r = run_cli("render s.scn --mode normal -o a.hdr -o ./a.hdr", dir);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("are one file"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/a.hdr"));
}

// A link whose target does not exist yet leads to the file a write through it creates, so
// two outputs can be one file before either is written. Each run below must be refused before
// any work, naming the collision, and leave no file at the shared target.
TEST(CliInputs, OutputsThatMeetThroughDanglingLinksAreRefused) {
  std::string dir = temp_dir();
  write_file(dir + "/s.scn", kScene);
  fs::create_directory(dir + "/sub");
  fs::create_symlink("sub", dir + "/dirlink");
  fs::create_symlink("f.film", dir + "/to-film.hdr");
  fs::create_symlink("f.film", dir + "/s.hdr");  // the default output's name
  fs::create_symlink("a.hdr", dir + "/to-a.hdr");
  fs::create_symlink("to-a.hdr", dir + "/chain.hdr");           // a link to a link
  fs::create_symlink("dirlink/../a.hdr", dir + "/dotdot.hdr");  // `..` after a folder link
  fs::create_symlink(dir + "/a.hdr", dir + "/absolute.hdr");    // an absolute target
  fs::create_symlink("../a.hdr", dir + "/sub/up.hdr");          // read in the link's folder
  fs::create_symlink("a.hdr", dir + "/a.albedo.pfm");           // an AOV sibling
  fs::create_symlink("a.hdr", dir + "/a.4.hdr");                // a --save-at image
  fs::create_symlink("f.film", dir + "/stats.json");
  fs::create_symlink("a.hdr", dir + "/stats-a.json");
  for (std::string args : {
           "render s.scn --spp 1 -o to-film.hdr --checkpoint f.film",
           "render s.scn --spp 1 --checkpoint f.film",
           "render s.scn --spp 1 -o a.hdr -o to-a.hdr",
           "render s.scn --spp 1 -o a.hdr -o chain.hdr",
           "render s.scn --spp 1 -o a.hdr -o dotdot.hdr",
           "render s.scn --spp 1 -o a.hdr -o absolute.hdr",
           "render s.scn --spp 1 -o a.hdr -o dirlink/up.hdr",
           "render s.scn --spp 1 -o a.hdr --aov albedo",
           "render s.scn --spp 4 -o a.hdr --save-at 4",
           "render s.scn --spp 1 -o a.hdr --checkpoint f.film --stats-json stats.json",
           "render s.scn --spp 1 -o a.hdr --stats-json stats-a.json",
       }) {
    auto r = run_cli(args, dir);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("are one file"), std::string::npos) << args << "\n" << r.out;
    EXPECT_FALSE(fs::exists(dir + "/a.hdr")) << args;
    EXPECT_FALSE(fs::exists(dir + "/f.film")) << args;
  }
  // A link to a different file that does not exist yet is only a name: the run goes ahead and
  // writes through it, keeping the link.
  fs::create_symlink("b.hdr", dir + "/to-b.hdr");
  auto ok = run_cli("render s.scn --mode normal -o a.hdr -o to-b.hdr", dir);
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_TRUE(fs::is_regular_file(dir + "/b.hdr"));
  EXPECT_TRUE(fs::is_symlink(dir + "/to-b.hdr"));
}

// The film is read whole before the render starts and saved with more passes: continuing a
// render into its own checkpoint loses nothing, so it stays allowed.
TEST(CliInputs, ACheckpointMayContinueItsOwnResumeFilm) {
  std::string dir = temp_dir();
  write_file(dir + "/s.scn", kScene);
  ASSERT_EQ(run_cli("render s.scn --spp 1 --checkpoint f.film -o a.hdr -q", dir).status, 0);
  auto r = run_cli("render s.scn --spp 2 --resume f.film --checkpoint f.film -o b.hdr -q", dir);
  EXPECT_EQ(r.status, 0) << r.out;
  auto again = run_cli("render s.scn --spp 2 --resume f.film -o c.hdr -q", dir);
  EXPECT_EQ(again.status, 0) << again.out;
  EXPECT_EQ(read_file(dir + "/b.hdr"), read_file(dir + "/c.hdr"));
}

// A FIFO would block a reader for ever; a directory is no file. Every input channel says
// "not a regular file" and exits 2 within the timeout.
TEST(CliInputs, FifosAndDirectoriesAreNotReadAndDoNotHang) {
  std::string dir = temp_dir();
  ASSERT_EQ(::mkfifo((dir + "/pipe").c_str(), 0600), 0);
  fs::create_directory(dir + "/folder");
  write_file(dir + "/m.scn", std::string(kScene) + "mesh pipe.ply 0 0 0 1\n");
  ASSERT_EQ(::mkfifo((dir + "/pipe.ply").c_str(), 0600), 0);
  fs::copy_file(source_path("scenes/letterX.ply"), dir + "/x.tris.ply");
  for (std::string args :
       {"render pipe", "info pipe", "render m.scn", "trace pipe.ply none.rays",
        "convert pipe out.png", "diff pipe pipe", "render s.scn --resume pipe"}) {
    if (args.find("s.scn") != std::string::npos) write_file(dir + "/s.scn", kScene);
    auto r = run_cli(args, dir, 20);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("not a regular file"), std::string::npos) << args << "\n" << r.out;
  }
  // A directory given as the scene is named as one (CliMessages has the other kinds).
  auto folder = run_cli("render folder", dir, 20);
  EXPECT_EQ(folder.status, 2) << folder.out;
  EXPECT_NE(folder.out.find("folder: a directory, not a scene file"), std::string::npos)
      << folder.out;
}

// A mesh file that names a FIFO (an OBJ's material library, a glTF's buffer) must not hang
// Assimp: the named file is refused, the mesh loads without it or fails naming it.
TEST(CliInputs, FilesAMeshNamesAreRegularFilesToo) {
  std::string dir = temp_dir();
  ASSERT_EQ(::mkfifo((dir + "/pipe.mtl").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir + "/pipe.bin").c_str(), 0600), 0);
  write_file(dir + "/tri.obj", "mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(dir + "/obj.scn", std::string(kScene) + "mesh tri.obj 0 0 0 1\n");
  auto obj = run_cli("info obj.scn", dir, 20);
  EXPECT_NE(obj.status, 124) << obj.out;  // no hang
  EXPECT_NE(obj.out.find("triangles"), std::string::npos) << obj.out;
  write_file(dir + "/tri.gltf",
             R"({"asset":{"version":"2.0"},"buffers":[{"uri":"pipe.bin","byteLength":36}],)"
             R"("bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,)"
             R"("componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],)"
             R"("scenes":[{"nodes":[0]}],"scene":0})");
  write_file(dir + "/gltf.scn", std::string(kScene) + "mesh tri.gltf 0 0 0 1\n");
  auto gltf = run_cli("info gltf.scn", dir, 20);
  EXPECT_EQ(gltf.status, 2) << gltf.out;
  EXPECT_NE(gltf.out.find("pipe.bin"), std::string::npos) << gltf.out;
  EXPECT_NE(gltf.out.find("not a regular file"), std::string::npos) << gltf.out;
}

}  // namespace
}  // namespace raylane
