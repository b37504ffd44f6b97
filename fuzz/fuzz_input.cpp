#include "fuzz/fuzz_input.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace sublift::fuzz {
namespace {

// One mkdtemp folder per process, removed at exit so runs of millions of inputs leave nothing.
struct PrivateDir {
  std::string path;
  PrivateDir() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/sublift-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) {
      std::perror("sublift fuzz: mkdtemp");
      std::abort();
    }
    path = pattern;
  }
  ~PrivateDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

std::string write_private_file(const std::string& name, const std::string& bytes) {
  static PrivateDir dir;
  const std::string path = dir.path + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::perror("sublift fuzz: write");
    std::abort();
  }
  return path;
}

}  // namespace sublift::fuzz
