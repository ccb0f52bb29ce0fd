// Writes letterX.ply and letterY.ply, the flat letters of the CS500 test scene, from the
// corner points given in docs/scene-language.md ("The letter meshes").
// Usage: make_letters OUTPUT_DIR
#include <cstdio>
#include <string>
#include <vector>

namespace {

struct Point {
  const char* x;
  const char* y;
};

struct Letter {
  const char* name;
  std::vector<Point> vertices;
  std::vector<std::vector<int>> faces;
};

// The points are written exactly as the spec gives them (as text), so the files are
// reproducible byte for byte.
const Letter kLetters[] = {
    {"letterX",
     {{"0.452666", "1.443985"},
      {"0.815189", "1.274938"},
      {"-0.452666", "-1.443985"},
      {"-0.815189", "-1.274938"},
      {"-0.815189", "1.274938"},
      {"-0.452666", "1.443985"},
      {"0.815189", "-1.274938"},
      {"0.452666", "-1.443985"}},
     {{3, 2, 1, 0}, {7, 6, 5, 4}}},
    {"letterY",
     {{"-0.181262", "0.084524"},
      {"0.181262", "-0.084524"},
      {"-0.452666", "-1.443985"},
      {"-0.815189", "-1.274938"},
      {"-0.181262", "-0.084524"},
      {"0.181262", "0.084524"},
      {"0.815189", "-1.274938"},
      {"0.452666", "-1.443985"},
      {"0.2", "0"},
      {"-0.2", "0"},
      {"-0.2", "1.5"},
      {"0.2", "1.5"}},
     {{3, 2, 1, 0}, {7, 6, 5, 4}, {11, 10, 9, 8}}},
};

bool write_letter(const std::string& dir, const Letter& letter) {
  std::string path = dir + "/" + letter.name + ".ply";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) {
    std::fprintf(stderr, "make_letters: cannot write %s\n", path.c_str());
    return false;
  }
  std::fprintf(f,
               "ply\nformat ascii 1.0\ncomment %s of the CS500 test scene (raylane "
               "tools/make_letters)\nelement vertex %zu\nproperty float x\nproperty float "
               "y\nproperty float z\nelement face %zu\nproperty list uchar int "
               "vertex_indices\nend_header\n",
               letter.name, letter.vertices.size(), letter.faces.size());
  for (const Point& p : letter.vertices)
    std::fprintf(f, "%s %s 0\n", p.x, p.y);
  for (const auto& face : letter.faces) {
    std::fprintf(f, "%zu", face.size());
    for (int i : face)
      std::fprintf(f, " %d", i);
    std::fprintf(f, "\n");
  }
  return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_letters OUTPUT_DIR\n");
    return 2;
  }
  for (const Letter& letter : kLetters)
    if (!write_letter(argv[1], letter)) return 1;
  return 0;
}
