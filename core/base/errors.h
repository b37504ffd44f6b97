#pragma once
// Typed exceptions thrown at core's API entry points. Messages name the file, the line (or byte
// offset) and what is wrong, so the CLI and the GUI can show them as they are.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace sublift {

/// Base of every error Sublift raises on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file's content is wrong (structure, numbers, indices). `line` is 1-based, 0 when unknown.
class InputError : public Error {
 public:
  InputError(const std::string& file, std::size_t line, const std::string& what);
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::size_t line_;
};

/// A file cannot be opened, read or written.
class IoError : public Error {
 public:
  using Error::Error;
};

/// Long work stopped because its caller asked (a progress callback answered false); nothing
/// it would have changed has changed.
class Cancelled : public Error {
 public:
  using Error::Error;
};

/// A mesh or complex violates a topological precondition of an algorithm.
class TopologyError : public Error {
 public:
  using Error::Error;
};

}  // namespace sublift
