#pragma once
#include "core/complex/face_loop.h"
// Helpers for the file-format tests: temporary folders, error capture and comparisons of
// complexes that do not depend on edge or face numbering.
#include <algorithm>
#include <filesystem>
#include <unistd.h>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/complex/complex.h"
#include "core/base/errors.h"

namespace sublift::testing {

/// A fresh folder under the system temp folder, removed by the destructor; the process id in
/// its name keeps two test runs on one machine (a CI job beside a developer's) out of each other.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The InputError raised by `f` ("" if none); its line goes to `*line`.
inline std::string input_error(const std::function<void()>& f, std::size_t* line = nullptr) {
  try {
    f();
  } catch (const InputError& e) {
    if (line) *line = e.line();
    return e.what();
  }
  return "";
}

/// Expects `read(text, file)` to throw an InputError on `line` whose message names `file` and
/// contains `needle` (the readers' shared contract: file, line, what is wrong).
template <class Reader>
void expect_input_error(Reader read, const std::string& text, const std::string& file, std::size_t line,
                        const std::string& needle) {
  std::size_t got = 12345;
  const std::string e = input_error([&] { read(text, file); }, &got);
  EXPECT_NE(e.find(needle), std::string::npos) << "message: " << e << "\nfile:\n" << text;
  EXPECT_EQ(got, line) << e;
  EXPECT_NE(e.find(file), std::string::npos) << e;
}

/// Feature dims keyed by vertex indices (independent of edge/face numbering): vertex -> dim,
/// sorted edge -> dim, canonical face loop -> dim.
struct DimsByVertices {
  std::vector<std::uint8_t> vertices;
  std::map<std::vector<std::uint32_t>, std::uint8_t> edges, faces;
  bool operator==(const DimsByVertices&) const = default;
};


inline DimsByVertices dims_by_vertices(const Complex& c) {
  DimsByVertices d;
  d.vertices = c.vertex_dim;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
    d.edges[{std::min(a, b), std::max(a, b)}] = c.edge_dim[e];
  }
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) d.faces[canonical_loop(c.faces.row(f))] = c.face_dim[f];
  return d;
}

/// Random positions (3 per vertex) that are exact binary fractions times awkward scales.
inline std::vector<double> awkward_positions(std::uint32_t nv, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(3 * std::size_t(nv));
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = u(rng) * (i % 3 == 0 ? 1e-7 : i % 3 == 1 ? 1.0 / 3.0 : 1e9);
  return x;
}

}  // namespace sublift::testing
