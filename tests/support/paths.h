// Where the tests find the repository's files and the built command-line program.
#pragma once

#include <string>

namespace raylane::testing {

std::string source_path(const std::string& relative);  // a path inside the repository
std::string cli_path();                                // the built `raylane` program
std::string temp_dir();  // a fresh, empty directory for this test, removed at exit

// A whole file's bytes (empty if it cannot be read), and a file written with `bytes`.
std::string read_file(const std::string& path);
void write_file(const std::string& path, const std::string& bytes);
// A temp_dir() holding `scene` as s.scn, for the CLI tests that render a small scene.
std::string dir_with_scene(const std::string& scene);

}  // namespace raylane::testing
