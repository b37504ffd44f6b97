#pragma once
// Bounds-checked reading of fixed-size binary values (either endianness) from a byte buffer.
// Every read checks the remaining length first, so a lying count can never read past the end.
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/base/errors.h"

namespace sublift {

/// The T (arithmetic, 1/2/4/8 bytes) stored at `p` in the given byte order.
template <class T>
T load_endian(const void* p, bool big_endian) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, p, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  T v;
  std::memcpy(&v, raw, sizeof(T));
  return v;
}

/// Stores `v` at `p` in the given byte order.
template <class T>
void store_endian(void* p, T v, bool big_endian) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  std::memcpy(p, raw, sizeof(T));
}

class BinaryCursor {
 public:
  BinaryCursor(std::string_view bytes, std::size_t offset, std::string file, bool big_endian)
      : bytes_(bytes), pos_(offset), file_(std::move(file)), big_(big_endian) {}

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }

  /// Reads one T (arithmetic, 1/2/4/8 bytes); throws InputError naming `what` at EOF.
  template <class T>
  T read(const char* what) {
    if (remaining() < sizeof(T))
      throw InputError(file_, 0, std::string("unexpected end of file at byte offset ") +
                                     std::to_string(pos_) + " while reading " + what);
    const T v = load_endian<T>(bytes_.data() + pos_, big_);
    pos_ += sizeof(T);
    return v;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_;
  std::string file_;
  bool big_;
};

}  // namespace sublift
