#include "core/io/model/animation_export.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>

#include <tiny_gltf.h>

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/model/model_source.h"
#include "core/io/model/surface_export.h"

namespace sublift {
namespace {

template <class T>
std::size_t append_le(std::vector<unsigned char>& buf, const std::vector<T>& values) {
  while (buf.size() % 4 != 0) buf.push_back(0);  // accessors start 4-byte aligned
  const std::size_t at = buf.size();
  buf.resize(at + values.size() * sizeof(T));
  std::memcpy(buf.data() + at, values.data(), values.size() * sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    for (std::size_t i = at; i < buf.size(); i += sizeof(T)) std::reverse(buf.begin() + i, buf.begin() + i + sizeof(T));
  return at;
}

struct Writer {
  tinygltf::Model m;
  tinygltf::Buffer buffer;
  // Appends values as a view + accessor; vec3 float accessors get min/max.
  template <class T>
  int add(const std::vector<T>& values, int component, int type, std::size_t count, int target, bool bounds) {
    const std::size_t at = append_le(buffer.data, values);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = at;
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    m.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = int(m.bufferViews.size()) - 1;
    a.componentType = component;
    a.type = type;
    a.count = count;
    if (bounds) {
      const std::size_t width = values.size() / count;
      a.minValues.assign(width, std::numeric_limits<double>::infinity());
      a.maxValues.assign(width, -std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < values.size(); ++i) {
        a.minValues[i % width] = std::min(a.minValues[i % width], double(values[i]));
        a.maxValues[i % width] = std::max(a.maxValues[i % width], double(values[i]));
      }
    }
    m.accessors.push_back(a);
    return int(m.accessors.size()) - 1;
  }
};

std::vector<float> to_float(const std::string& path, std::span<const double> x, std::size_t frame) {
  std::vector<float> f(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    f[i] = float(x[i]);
    if (!std::isfinite(f[i]))
      throw InputError(path, 0, "frame " + std::to_string(frame) + ", vertex " + std::to_string(i / 3) + ": not a finite float32");
  }
  return f;
}

std::vector<float> unit_normals(const Csr& faces, std::span<const double> xyz) {
  const std::vector<double> n = grouped_normals(faces, xyz, {});
  std::vector<float> f(n.size());
  for (std::size_t v = 0; v < n.size(); v += 3) {
    float c[3] = {float(n[v]), float(n[v + 1]), float(n[v + 2])};
    const float len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (!(len > 0)) c[0] = 0, c[1] = 0, c[2] = 1;
    else for (float& k : c) k /= len;
    std::copy_n(c, 3, &f[v]);
  }
  return f;
}

}  // namespace

void write_animation_gltf(const std::string& path, const Csr& faces, std::span<const double> frames,
                          std::span<const double> times, bool cyclic, double loop_end) {
  const std::string ext = file_extension(path);
  if (ext != "gltf" && ext != "glb") throw InputError(path, 0, "an animation is written to .gltf or .glb, not '." + ext + "'");
  const std::size_t n = times.size();
  if (n < 2) throw InputError(path, 0, "an animation needs at least 2 frames");
  if (frames.size() % (3 * n) != 0) throw InputError(path, 0, "frames are not 3 values per vertex per frame");
  const std::size_t nv = frames.size() / (3 * n);
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1])))
      throw InputError(path, 0, "frame times must increase: frame " + std::to_string(i) + " is at " + std::to_string(times[i]));
  if (cyclic && !(loop_end > times[n - 1])) throw InputError(path, 0, "a cyclic animation's loop must end after its last frame");
  std::vector<std::uint32_t> tri;
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto c = faces.row(f);
    for (std::uint32_t v : c)
      if (v >= nv) throw InputError(path, 0, "face " + std::to_string(f) + " names vertex " + std::to_string(v) + ", beyond " + std::to_string(nv));
    for (std::size_t i = 1; i + 1 < c.size(); ++i) tri.insert(tri.end(), {c[0], c[i], c[i + 1]});
  }
  if (tri.empty()) throw InputError(path, 0, "glTF needs at least one face");
  const double bytes = double(n) * 24.0 * double(nv) + 4.0 * double(tri.size()) + 4.0 * double(n + 1) * double(n);
  if (bytes > double(std::numeric_limits<std::uint32_t>::max()) - (1 << 20))
    throw InputError(path, 0, "the animation needs more than 4 GB of glTF buffer (fewer frames or a coarser level)");

  Writer w;
  w.m.asset.version = "2.0";
  w.m.asset.generator = "Sublift";
  const std::vector<float> p0 = to_float(path, frames.subspan(0, 3 * nv), 0);
  const std::vector<float> n0 = unit_normals(faces, frames.subspan(0, 3 * nv));
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = w.add(p0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  prim.attributes["NORMAL"] = w.add(n0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  prim.indices = w.add(tri, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, tri.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, false);
  for (std::size_t f = 1; f < n; ++f) {
    const std::span<const double> x = frames.subspan(f * 3 * nv, 3 * nv);
    std::vector<float> dp = to_float(path, x, f), dn = unit_normals(faces, x);
    for (std::size_t i = 0; i < dp.size(); ++i) dp[i] -= p0[i], dn[i] -= n0[i];
    std::map<std::string, int> target;
    target["POSITION"] = w.add(dp, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    target["NORMAL"] = w.add(dn, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    prim.targets.push_back(target);
  }
  // Keys: frame i at times[i] with target i alone (frame 0: none); cyclic: back to frame 0.
  std::vector<float> key_times(times.begin(), times.end());
  if (cyclic) key_times.push_back(float(loop_end));
  for (std::size_t i = 1; i < key_times.size(); ++i)
    if (!(key_times[i] > key_times[i - 1]))
      throw InputError(path, 0, "frame times " + std::to_string(times[i - 1]) + " and the next are equal in float32");
  std::vector<float> weights(key_times.size() * (n - 1), 0.0f);
  for (std::size_t i = 1; i < n; ++i) weights[i * (n - 1) + (i - 1)] = 1.0f;
  tinygltf::AnimationSampler sampler;
  sampler.input = w.add(key_times, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, key_times.size(), -1, true);
  sampler.output = w.add(weights, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, weights.size(), -1, false);
  for (tinygltf::BufferView& v : w.m.bufferViews)
    if (v.target == -1) v.target = 0;  // animation data: no buffer target
  sampler.interpolation = "LINEAR";
  tinygltf::Animation anim;
  anim.name = "Sublift frames";
  anim.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  anim.channels.push_back(channel);
  w.m.animations.push_back(anim);

  tinygltf::Mesh mesh;
  mesh.name = "animation";
  mesh.primitives.push_back(prim);
  mesh.weights.assign(n - 1, 0.0);
  w.m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = "animation";
  node.mesh = 0;
  w.m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.name = "Sublift";
  scene.nodes = {0};
  w.m.scenes.push_back(scene);
  w.m.defaultScene = 0;
  w.m.buffers.push_back(std::move(w.buffer));

  const bool binary = ext == "glb";
  std::ostringstream out(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&w.m, out, /*prettyPrint=*/!binary, binary) || !out)
    throw IoError(path + ": cannot serialise glTF");
  const std::string data = std::move(out).str();
  write_file_atomic(path, [&](std::ostream& o) { o.write(data.data(), std::streamsize(data.size())); }, true);
}

std::string sequence_file_name(const std::string& pattern, int frame) {
  const std::filesystem::path p(pattern);
  std::string name = p.filename().string();
  const std::size_t first = name.find('#');
  std::string number = std::to_string(frame);
  if (first == std::string::npos) {
    const std::size_t dot = name.rfind('.');
    number.insert(0, number.size() < 4 ? 4 - number.size() : 0, '0');
    name.insert(dot == std::string::npos ? name.size() : dot, "_" + number);
  } else {
    std::size_t last = first;
    while (last < name.size() && name[last] == '#') ++last;
    const std::size_t width = last - first;
    number.insert(0, number.size() < width ? width - number.size() : 0, '0');
    name.replace(first, width, number);
  }
  return (p.parent_path() / name).string();
}

std::vector<std::string> write_frame_sequence(const std::string& pattern, const Csr& faces, std::span<const double> frames,
                                              std::size_t num_frames) {
  if (num_frames == 0 || frames.size() % (3 * num_frames) != 0) throw InputError(pattern, 0, "frames are not 3 values per vertex per frame");
  const std::size_t nv = frames.size() / (3 * num_frames);
  std::vector<std::string> names;
  for (std::size_t f = 0; f < num_frames; ++f) {
    const std::span<const double> x = frames.subspan(f * 3 * nv, 3 * nv);
    const std::vector<double> normals = grouped_normals(faces, x, {});
    names.push_back(sequence_file_name(pattern, int(f)));
    write_surface_with_normals(names.back(), faces, x, normals);
  }
  return names;
}

}  // namespace sublift
