#include "raylane/scene/mesh_guard.h"

#include "raylane/core/strings.h"
#include "raylane/scene/ply.h"

namespace raylane {

Status check_mesh_plausible(std::string_view head, uint64_t file_size, const std::string& name) {
  if (file_size > kMaxMeshFileBytes) return Error{cat("mesh ", quote_path(name), " is over 4 GiB")};
  if (!is_ply(head, name)) return ok_status();
  auto header = read_ply_header(head, name);
  if (!header) return Error{header.error()};
  return check_ply_plausible(*header, file_size, name);
}

}  // namespace raylane
