#pragma once
// Bounds-checked reading of fixed-size binary values (either endianness) from a byte buffer.
// Every read checks the remaining length first, so a lying count can never read past the end.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/base/errors.h"

namespace sublift {

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
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (big_ != (std::endian::native == std::endian::big))
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return v;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_;
  std::string file_;
  bool big_;
};

}  // namespace sublift
