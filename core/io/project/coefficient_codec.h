#pragma once
// How a project (version 2, docs/file_formats.md) stores its coefficients:
//   dense      f64 per value, as version 1;
//   sparse     the level-0 scaling coefficients as f64, then one bit per wavelet vertex (LSB
//              first) and the f64 values of the vertices whose bit is set: a wavelet that is zero
//              in every channel (after compression, or everywhere in a pure subdivision) takes
//              one bit;
//   quantized  the same mask, then a step per wavelet level and channel (f64), then each stored
//              value as a signed little-endian integer of 8, 16 or 32 bits times its step
//              (lossy: the error is reported).
// Lossless saves pick sparse where it is smaller than dense. "Zero" is the bit pattern 0, so
// -0.0 is kept and a lossless round trip is bit for bit.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sublift {

enum class CoefficientEncoding : std::uint8_t { Dense, Sparse, Quantized };

/// "dense", "sparse", "quantized".
std::string encoding_name(CoefficientEncoding e);
/// Parses a name; false when unknown.
bool parse_encoding(std::string_view name, CoefficientEncoding& e);

/// Quantization widths a project can hold.
bool valid_quantize_bits(int bits);

struct EncodedCoefficients {
  CoefficientEncoding encoding = CoefficientEncoding::Dense;
  std::uint64_t stored_vertices = 0;  // wavelet vertices whose values are stored (sparse, quantized)
  int bits = 0;                       // quantized
  std::string bytes;                  // this part of the payload
  double max_error = 0.0;             // quantized: the largest |coefficient - stored value|
};

/// `level_vertices` holds the vertex counts of levels 0..J (so level l's wavelets sit on vertices
/// level_vertices[l] .. level_vertices[l + 1] - 1). `bits` 0: lossless (sparse where smaller);
/// 8, 16 or 32: quantized.
EncodedCoefficients encode_coefficients(std::span<const double> coeffs, std::span<const std::uint32_t> level_vertices,
                                        int channels, int bits);

/// Bytes an encoding takes, in doubles so that a header's lying counts cannot wrap: N values,
/// V0 base vertices, `levels` wavelet levels, `stored` stored wavelet vertices.
double encoded_bytes(CoefficientEncoding e, double N, double V0, int channels, int levels, double stored, int bits);

/// Decodes `payload` (exactly encoded_bytes long) into N values. Throws InputError(file, 0, ...)
/// when the mask disagrees with `stored`, its padding bits are set, or a step is not a finite
/// non-negative number.
std::vector<double> decode_coefficients(std::string_view payload, CoefficientEncoding e, std::size_t N,
                                        std::span<const std::uint32_t> level_vertices, int channels,
                                        std::uint64_t stored, int bits, const std::string& file);

}  // namespace sublift
