#include "core/base/file_io.h"

#include <filesystem>
#include <fstream>
#include <atomic>
#include <system_error>

#include "core/base/errors.h"
#include "core/base/temp_files.h"
#include "core/base/text_lines.h"

namespace sublift {
namespace fs = std::filesystem;

std::string read_file_bytes(const std::string& path, std::size_t max_bytes) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw IoError(path + ": no such file");
  if (fs::is_directory(st)) throw IoError(path + ": is a directory, not a file");
  if (!fs::is_regular_file(st)) throw IoError(path + ": not a regular file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw IoError(path + ": cannot read size: " + ec.message());
  if (size > max_bytes)
    throw IoError(path + ": file of " + std::to_string(size) + " bytes exceeds the limit of " +
                  std::to_string(max_bytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::size_t>(in.gcount()) != size) throw IoError(path + ": read error");
  return bytes;
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& writer,
                       bool binary) {
  const fs::path target(path);
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw IoError(path + ": folder " + dir.string() + " does not exist");
  install_interrupt_cleanup();
  remove_stale_temp_files(path);
  static std::atomic<unsigned long> saves{0};
  const fs::path tmp = dir / temp_file_name(target.filename().string(), saves++);
  const int slot = register_temp_file(tmp.string());
  struct Forget {  // after the rename or the removal below, whichever ends the save
    int slot;
    ~Forget() { unregister_temp_file(slot); }
  } forget{slot};
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
      if (!out) throw IoError(path + ": cannot create " + tmp.string());
      writer(out);
      out.flush();
      if (!out) throw IoError(path + ": write failed (disk full?)");
    }
    fs::rename(tmp, target, ec);
    if (ec) throw IoError(path + ": cannot replace file: " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

std::string file_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
  return to_lower(ext);
}

}  // namespace sublift
