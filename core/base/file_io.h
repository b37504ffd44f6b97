#pragma once
// Whole-file reading with a size cap, and atomic writing (temp file + rename), so a failed save
// never destroys the previous good file.
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>

namespace sublift {

/// Reads a regular file completely. Throws IoError (missing, a directory, unreadable, larger
/// than max_bytes).
std::string read_file_bytes(const std::string& path, std::size_t max_bytes = std::size_t(1) << 32);

/// Writes through `writer` into `path.tmp-PID-N` beside `path`, flushes, then renames over
/// `path`. On any failure the temp file is removed, `path` is untouched and IoError is thrown.
/// SIGINT or SIGTERM during the save removes the temp file (core/base/temp_files.h). Before
/// writing, leftovers of earlier saves of `path` are removed: `path.tmp-PID-N` whose process is
/// no longer alive (or is this one, not saving it now), and older names without a PID.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& writer,
                       bool binary = false);

/// Lower-case extension without the dot ("obj"), empty if none.
std::string file_extension(const std::string& path);

}  // namespace sublift
