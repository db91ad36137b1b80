// Reading an input file the user names (a scene, a pwl waveform's CSV, a study's variants)
// without letting it hang or exhaust memory: only a regular file, opened without blocking
// (a FIFO swapped in after a check cannot block the open) and checked on its descriptor, read to
// at most a limit whatever its size said.
#pragma once

#include <cstddef>
#include <string>

namespace emnet {

/// The bytes of `path` [at most `limit`]. `what` names the file in messages ("a scene file",
/// "the pwl file 'x.csv'").
/// @param limit  the most bytes the file may have [bytes]
/// @param key    the key the InputError names
/// @throws InputError(where = path, key = `key`):
///   "cannot open WHAT (no such file)" / "(it is a directory)" / "(<strerror>)",
///   "not a regular file (a pipe); WHAT is read from a regular file" (also character and block
///   devices, sockets),
///   "the file is N bytes; WHAT may have at most LIMIT bytes" (also when it grew while read),
///   "cannot read WHAT (<strerror>)".
std::string read_bounded_regular_file(const std::string& path, std::size_t limit,
                                      const std::string& what, const std::string& key = "");

}  // namespace emnet
