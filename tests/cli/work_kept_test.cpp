// Work is never thrown away (README.md, "Using it"): a --checkpoint film that exists is refused
// unless it is the film resumed, SIGTERM and SIGUSR1 stop a render like Ctrl-C (the image so far
// written), and bare `raylane` prints the usage instead of rendering over ./testscene.hdr.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "support/cli_run.h"
#include "support/paths.h"

extern char** environ;

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::cli_path;
using testing::run_cli;
using testing::source_path;
using testing::temp_dir;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

const char* kTinyScene =
    "screen 4 4\ncamera 0 0 5 1\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\nlight 1 1 1\n"
    "sphere 0 3 3 1\n";

TEST(CliWorkKept, AnExistingCheckpointFilmIsOnlyContinuedNeverReplaced) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/tiny.scn") << kTinyScene;
  ASSERT_EQ(run_cli("render tiny.scn --spp 3 --checkpoint f.film -o a.hdr -q", dir).status, 0);
  std::string film = read_file(dir + "/f.film");
  ASSERT_GT(film.size(), 100u);
  for (std::string again : {"render tiny.scn --spp 5 --checkpoint f.film -o b.hdr -q",
                            "render tiny.scn --spp 5 --resume a.hdr --checkpoint f.film -q",
                            "tiny.scn --spp 1 --checkpoint ./f.film -o b.hdr"}) {
    auto r = run_cli(again, dir);
    EXPECT_EQ(r.status, 2) << again << "\n" << r.out;
    EXPECT_NE(r.out.find("f.film already exists and would be replaced at the first checkpoint; "
                         "continue it with --resume"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(read_file(dir + "/f.film"), film) << again;
    EXPECT_FALSE(fs::exists(dir + "/b.hdr"));
  }
  // The film resumed may be saved again with more passes; a ray-casting view writes no film.
  auto resumed = run_cli("render tiny.scn --spp 5 --resume f.film --checkpoint f.film -q", dir);
  EXPECT_EQ(resumed.status, 0) << resumed.out;
  EXPECT_NE(read_file(dir + "/f.film"), film);
  EXPECT_EQ(run_cli("render tiny.scn --mode normal --checkpoint f.film -o n.hdr -q", dir).status,
            0);
}

// Starts a long render, sends `sig` once it is under way, and returns the exit status; the
// image goes to `out`.
int render_and_signal(int sig, const std::string& out) {
  std::string exe = cli_path(), scene = source_path("scenes/testscene.scn");
  std::vector<std::string> args = {exe, "render", scene, "--spp", "1000000", "--quiet", "-o", out};
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid;
  if (posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, sig);
  int st = 0;
  if (waitpid(pid, &st, 0) != pid || !WIFEXITED(st)) return -1;
  return WEXITSTATUS(st);
}

// `timeout`, batch schedulers and `kill` send SIGTERM: on one process it ends the render after
// the pass in flight like Ctrl-C, with the image so far and status 130; so does SIGUSR1.
TEST(CliWorkKept, SigtermAndSigusr1WriteTheImageSoFarLikeCtrlC) {
  std::string dir = temp_dir();
  for (int sig : {SIGTERM, SIGUSR1}) {
    std::string out = dir + "/sig" + std::to_string(sig) + ".hdr";
    EXPECT_EQ(render_and_signal(sig, out), 130) << "signal " << sig;
    std::string text = read_file(out);
    auto at = text.find("RAYLANE_SPP=");
    ASSERT_NE(at, std::string::npos) << "signal " << sig << ": no image";
    int spp = std::atoi(text.c_str() + at + 12);
    EXPECT_GE(spp, 1);
    EXPECT_LT(spp, 1000000);
  }
}

// The output's folder disappears while the render runs (the first saved checkpoint says it
// has started): the image goes to a rescue file, the film is kept beside it, the status is 1,
// and the kept film, resumed with the pass count the message gives, writes the same image
// without rendering.
TEST(CliWorkKept, AnOutputLostAtWriteTimeKeepsTheImageAndTheFilm) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/s.scn") << kTinyScene;
  std::filesystem::create_directory(dir + "/out");
  const std::string cmd =
      "cd '" + dir + "' && { timeout -k 5 60 '" + cli_path() +
      "' render s.scn --spp 1000000 --time 3 --checkpoint c.film --checkpoint-every 0 "
      "-o out/a.pfm > log 2>&1 & pid=$!; until [ -e c.film ]; do sleep 0.02; done; "
      "rm -rf out; wait $pid; echo $? > status; }";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string log = read_file(dir + "/log");
  EXPECT_EQ(std::atoi(read_file(dir + "/status").c_str()), 1) << log;
  const std::string image_tag = "the image is saved as ", film_tag = "film is kept as ";
  auto image_at = log.find(image_tag), film_at = log.find(film_tag);
  ASSERT_NE(image_at, std::string::npos) << log;
  ASSERT_NE(film_at, std::string::npos) << log;
  auto name_after = [&](std::size_t at) {
    return log.substr(at, log.find_first_of(":\n", at) - at);
  };
  const std::string rescue_image = name_after(image_at + image_tag.size());
  const std::string rescue_film = name_after(film_at + film_tag.size());
  auto spp_at = log.find("--spp ", film_at);
  ASSERT_NE(spp_at, std::string::npos) << log;
  const int spp = std::atoi(log.c_str() + spp_at + 6);
  EXPECT_GE(spp, 1);
  auto again = run_cli(
      "render s.scn -q -o again.pfm --spp " + std::to_string(spp) + " --resume " + rescue_film,
      dir);
  ASSERT_EQ(again.status, 0) << again.out;
  EXPECT_EQ(read_file(dir + "/again.pfm"), read_file(dir + "/" + rescue_image));
}

// A resumed render goes on saving into the film it continues, so stopping it loses nothing
// of what it added; --no-checkpoint leaves the film as it was.
TEST(CliWorkKept, AResumedRenderSavesIntoTheFilmItContinues) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/s.scn") << kTinyScene;
  ASSERT_EQ(run_cli("render s.scn -q --spp 2 --checkpoint f.film -o a.hdr", dir).status, 0);
  auto resumed = run_cli("render s.scn -q --spp 5 --resume f.film -o b.hdr", dir);
  ASSERT_EQ(resumed.status, 0) << resumed.out;
  EXPECT_NE(run_cli("info f.film", dir).out.find("spp: 5"), std::string::npos);
  auto left = run_cli("render s.scn -q --spp 7 --resume f.film --no-checkpoint -o c.hdr", dir);
  ASSERT_EQ(left.status, 0) << left.out;
  EXPECT_NE(run_cli("info f.film", dir).out.find("spp: 5"), std::string::npos);
  // The film at 5 passes continued to 7 is the 7-pass render, and saved says so.
  ASSERT_EQ(run_cli("render s.scn -q --spp 7 --resume f.film -o d.hdr", dir).status, 0);
  EXPECT_EQ(read_file(dir + "/c.hdr"), read_file(dir + "/d.hdr"));
  EXPECT_NE(run_cli("info f.film", dir).out.find("spp: 7"), std::string::npos);
  auto both =
      run_cli("render s.scn --spp 9 --resume f.film --no-checkpoint --checkpoint g.film", dir);
  EXPECT_EQ(both.status, 2) << both.out;
}

TEST(CliWorkKept, BareRaylanePrintsTheUsageAndWritesNothing) {
  std::string dir = temp_dir();
  auto r = run_cli("", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("usage:\n  raylane render [SCENE] [options]"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace raylane
