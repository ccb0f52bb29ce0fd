// What a file given as the scene is when it is not a scene: a film, a mesh, an image, a ray
// set, another renderer's scene, binary data or a directory. Such a file read as scene lines
// gives a screenful of "unknown command" errors over escaped bytes; one line that names what
// the file looks like, and what raylane does with it, says more (docs/scene-language.md, "Error
// classes").
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace raylane::cli {

// The kind of file the first bytes (at most a few KiB) and the name show, for those that are
// not scenes; nothing when the bytes may be scene text.
std::optional<std::string> foreign_kind(std::string_view head, const std::string& path);

// One line for `path` given as a scene when it is not one ("room.film: a raylane film, not a
// scene: continue it with ..."), or nothing when it may be a scene (or cannot be read: the
// scene loader says why). Regular files are only read; a directory is named as one.
std::optional<std::string> not_a_scene(const std::string& path);

}  // namespace raylane::cli
