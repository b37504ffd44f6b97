#include "core/io/project/coefficient_codec.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"

namespace sublift {
namespace {

template <class T>
void append(std::string& out, T v) {
  char b[sizeof(T)];
  store_endian(b, v, false);
  out.append(b, sizeof(T));
}

// Whether wavelet vertex v (absolute index) holds anything: a bit pattern other than 0.
bool nonzero(std::span<const double> c, std::size_t v, std::size_t ch) {
  for (std::size_t k = 0; k < ch; ++k)
    if (std::bit_cast<std::uint64_t>(c[v * ch + k]) != 0) return true;
  return false;
}

std::int64_t quantize_max(int bits) { return (std::int64_t(1) << (bits - 1)) - 1; }

void append_quantized(std::string& out, std::int64_t q, int bits) {
  if (bits == 8) append(out, static_cast<std::int8_t>(q));
  else if (bits == 16) append(out, static_cast<std::int16_t>(q));
  else append(out, static_cast<std::int32_t>(q));
}

std::int64_t load_quantized(const char* p, int bits) {
  if (bits == 8) return load_endian<std::int8_t>(p, false);
  if (bits == 16) return load_endian<std::int16_t>(p, false);
  return load_endian<std::int32_t>(p, false);
}

}  // namespace

std::string encoding_name(CoefficientEncoding e) {
  return e == CoefficientEncoding::Dense ? "dense" : e == CoefficientEncoding::Sparse ? "sparse" : "quantized";
}

bool parse_encoding(std::string_view name, CoefficientEncoding& e) {
  for (const CoefficientEncoding x : {CoefficientEncoding::Dense, CoefficientEncoding::Sparse, CoefficientEncoding::Quantized})
    if (name == encoding_name(x)) return e = x, true;
  return false;
}

bool valid_quantize_bits(int bits) { return bits == 8 || bits == 16 || bits == 32; }

double encoded_bytes(CoefficientEncoding e, double N, double V0, int channels, int levels, double stored, int bits) {
  if (e == CoefficientEncoding::Dense) return 8.0 * N;
  const double ch = channels, wavelets = std::max(0.0, N / ch - V0);
  const double head = 8.0 * V0 * ch + std::ceil(wavelets / 8.0);
  if (e == CoefficientEncoding::Sparse) return head + 8.0 * stored * ch;
  return head + 8.0 * levels * ch + stored * ch * (bits / 8);
}

EncodedCoefficients encode_coefficients(std::span<const double> coeffs, std::span<const std::uint32_t> level_vertices,
                                        int channels, int bits) {
  const auto ch = static_cast<std::size_t>(channels);
  const std::size_t V0 = level_vertices.front(), V = coeffs.size() / ch, W = V - V0;
  const int levels = static_cast<int>(level_vertices.size()) - 1;
  EncodedCoefficients r;
  r.bits = bits;
  r.encoding = bits ? CoefficientEncoding::Quantized : CoefficientEncoding::Sparse;

  // Quantized: one step per level and channel, from the level's largest magnitude.
  std::vector<double> step;
  std::vector<std::int64_t> q;
  if (bits) {
    const std::int64_t qmax = quantize_max(bits);
    step.assign(static_cast<std::size_t>(levels) * ch, 0.0);
    q.assign(W * ch, 0);
    for (int l = 0; l < levels; ++l)
      for (std::size_t k = 0; k < ch; ++k) {
        double big = 0.0;
        for (std::size_t v = level_vertices[l]; v < level_vertices[l + 1]; ++v) big = std::max(big, std::abs(coeffs[v * ch + k]));
        const double s = big / static_cast<double>(qmax);
        step[static_cast<std::size_t>(l) * ch + k] = s;
        for (std::size_t v = level_vertices[l]; v < level_vertices[l + 1]; ++v) {
          const double w = coeffs[v * ch + k];
          const std::int64_t n = s > 0.0 ? std::clamp<std::int64_t>(std::llround(w / s), -qmax, qmax) : 0;
          q[(v - V0) * ch + k] = n;
          r.max_error = std::max(r.max_error, std::abs(w - static_cast<double>(n) * s));
        }
      }
  }
  const auto stored = [&](std::size_t i) {  // wavelet vertex V0 + i
    if (!bits) return nonzero(coeffs, V0 + i, ch);
    for (std::size_t k = 0; k < ch; ++k)
      if (q[i * ch + k] != 0) return true;
    return false;
  };
  std::string mask((W + 7) / 8, '\0');
  for (std::size_t i = 0; i < W; ++i)
    if (stored(i)) {
      mask[i / 8] = static_cast<char>(static_cast<unsigned char>(mask[i / 8]) | (1u << (i % 8)));
      ++r.stored_vertices;
    }
  const double sparse = encoded_bytes(r.encoding, double(coeffs.size()), double(V0), channels, levels,
                                      double(r.stored_vertices), bits);
  if (!bits && sparse >= 8.0 * double(coeffs.size())) {
    r.encoding = CoefficientEncoding::Dense;
    r.stored_vertices = 0;
    r.bytes.reserve(coeffs.size() * 8);
    for (const double x : coeffs) append(r.bytes, x);
    return r;
  }
  r.bytes.reserve(static_cast<std::size_t>(sparse));
  for (std::size_t i = 0; i < V0 * ch; ++i) append(r.bytes, coeffs[i]);
  r.bytes += mask;
  if (bits)
    for (const double s : step) append(r.bytes, s);
  for (std::size_t i = 0; i < W; ++i) {
    if (!stored(i)) continue;
    for (std::size_t k = 0; k < ch; ++k) {
      if (bits) append_quantized(r.bytes, q[i * ch + k], bits);
      else append(r.bytes, coeffs[(V0 + i) * ch + k]);
    }
  }
  return r;
}

std::vector<double> decode_coefficients(std::string_view payload, CoefficientEncoding e, std::size_t N,
                                        std::span<const std::uint32_t> level_vertices, int channels,
                                        std::uint64_t stored, int bits, const std::string& file) {
  std::vector<double> c(N, 0.0);
  const auto ch = static_cast<std::size_t>(channels);
  const char* p = payload.data();
  const auto f64 = [&] {
    const double x = load_endian<double>(p, false);
    p += 8;
    return x;
  };
  if (e == CoefficientEncoding::Dense) {
    for (double& x : c) x = f64();
    return c;
  }
  const std::size_t V0 = level_vertices.front(), W = N / ch - V0;
  const int levels = static_cast<int>(level_vertices.size()) - 1;
  for (std::size_t i = 0; i < V0 * ch; ++i) c[i] = f64();
  const auto* mask = reinterpret_cast<const unsigned char*>(p);
  p += (W + 7) / 8;
  std::uint64_t set = 0;
  for (std::size_t b = 0; b < (W + 7) / 8; ++b) set += static_cast<std::uint64_t>(std::popcount(mask[b]));
  if (W % 8 && (mask[W / 8] >> (W % 8)) != 0) throw InputError(file, 0, "coefficient mask: bits set past the last wavelet");
  if (set != stored)
    throw InputError(file, 0, "coefficient mask marks " + std::to_string(set) + " wavelet vertices, the header says " +
                                  std::to_string(stored));
  std::vector<double> step;
  if (e == CoefficientEncoding::Quantized)
    for (std::size_t i = 0; i < static_cast<std::size_t>(levels) * ch; ++i) {
      step.push_back(f64());
      if (!std::isfinite(step.back()) || step.back() < 0.0)
        throw InputError(file, 0, "quantization step " + std::to_string(i) + " is not a finite non-negative number");
    }
  int l = 0;
  for (std::size_t i = 0; i < W; ++i) {
    if (!(mask[i / 8] >> (i % 8) & 1u)) continue;
    const std::size_t v = V0 + i;
    while (v >= level_vertices[static_cast<std::size_t>(l) + 1]) ++l;
    for (std::size_t k = 0; k < ch; ++k) {
      if (e == CoefficientEncoding::Sparse) {
        c[v * ch + k] = f64();
      } else {
        c[v * ch + k] = static_cast<double>(load_quantized(p, bits)) * step[static_cast<std::size_t>(l) * ch + k];
        p += bits / 8;
      }
    }
  }
  return c;
}

}  // namespace sublift
