// Where the tests find the repository's files and the built command-line program.
#pragma once

#include <string>

namespace raylane::testing {

std::string source_path(const std::string& relative);  // a path inside the repository
std::string cli_path();                                // the built `raylane` program
std::string temp_dir();  // a fresh, empty directory for this test, removed at exit

}  // namespace raylane::testing
