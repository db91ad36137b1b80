// The bytes of a scene file (read_scene_file, emnet/scene/scene_reader.hpp): a regular file of
// at most scene_limits::file_bytes, read without reading past that.
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "emnet/scene/scene_reader.hpp"

namespace emnet {

std::string read_scene_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  const char* kind = nullptr;
  switch (status.type()) {
    case fs::file_type::not_found:
      throw InputError(path, "", "cannot open file");
    case fs::file_type::directory:
      throw InputError(path, "", "cannot open file (it is a directory)");
    case fs::file_type::character:
      kind = "a character device";
      break;
    case fs::file_type::block:
      kind = "a block device";
      break;
    case fs::file_type::fifo:
      kind = "a pipe";
      break;
    case fs::file_type::socket:
      kind = "a socket";
      break;
    default:
      break;
  }
  if (kind != nullptr) {
    throw InputError(
        path, "",
        std::string("not a regular file (") + kind + "); a scene is read from a " + "regular file");
  }
  const std::string limit = "a scene file may have at most " +
                            std::to_string(scene_limits::file_bytes) + " bytes (4 MiB)";
  const std::uintmax_t size = fs::file_size(path, error);
  if (!error && size > scene_limits::file_bytes) {
    throw InputError(path, "", "the file is " + std::to_string(size) + " bytes; " + limit);
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(path, "", "cannot open file");
  // Read at most one byte past the limit, whatever the size said (the file may have grown).
  std::string contents;
  char buffer[65536];
  while (contents.size() <= scene_limits::file_bytes) {
    stream.read(buffer, sizeof buffer);
    contents.append(buffer, static_cast<std::size_t>(stream.gcount()));
    if (!stream) break;
  }
  if (stream.bad()) throw InputError(path, "", "cannot read file");
  if (contents.size() > scene_limits::file_bytes) {
    throw InputError(
        path, "",
        "the file is larger than " + std::to_string(scene_limits::file_bytes) + " bytes; " + limit);
  }
  return contents;
}

}  // namespace emnet
