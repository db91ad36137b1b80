// The bytes of a scene file (read_scene_file, emnet/scene/scene_reader.hpp): a regular file of
// at most scene_limits::file_bytes, read without reading past that.

#include "emnet/core/bounded_file.hpp"
#include "emnet/scene/scene_reader.hpp"

namespace emnet {

std::string read_scene_file(const std::string& path) {
  return read_bounded_regular_file(path, scene_limits::file_bytes, "the scene file");
}

}  // namespace emnet
