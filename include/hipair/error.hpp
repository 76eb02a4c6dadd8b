// HIPAIR — typed errors. Library code never asserts or aborts on user input; it throws these.
#pragma once

#include <stdexcept>
#include <string>

namespace hipair {

/// Base of every error HIPAIR reports.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Invalid model input. `pointer()` is the JSON pointer of the offending value
/// (e.g. "/parts/1/loops/0/edges/3"), or "" for the whole document.
class ModelError : public Error {
 public:
  ModelError(std::string pointer, const std::string& reason)
      : Error(pointer.empty() ? reason : pointer + ": " + reason),
        pointer_(std::move(pointer)),
        reason_(reason) {}
  const std::string& pointer() const noexcept { return pointer_; }
  const std::string& reason() const noexcept { return reason_; }

 private:
  std::string pointer_;
  std::string reason_;
};

/// Geometry that the algorithms cannot handle (degenerate beyond what is supported).
class GeometryError : public Error {
 public:
  using Error::Error;
};

/// A numeric failure: a literal that does not parse, a division by zero, a non-finite value.
class NumericError : public Error {
 public:
  using Error::Error;
};

/// Failure to read or write a file.
class IoError : public Error {
 public:
  using Error::Error;
};

}  // namespace hipair
