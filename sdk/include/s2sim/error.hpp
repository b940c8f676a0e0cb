#pragma once
/// \file
/// The exception type of S2Sim. Every error raised for bad user input names where it comes
/// from: the file, the element path inside it and the attribute, when they are known.

#include <stdexcept>
#include <string>

namespace s2sim {

/// Where a value came from in a scene: `file` (as given, relative to the scene folder when it
/// is inside it), `element` (a path such as `robot/solids/cuboid[2]`), `attribute` (such as
/// `x`). Any part may be empty.
struct Location {
  std::string file;
  std::string element;
  std::string attribute;

  /// "file: element@attribute" with the empty parts left out.
  std::string str() const {
    std::string s = file;
    if (!element.empty()) s += (s.empty() ? "" : ": ") + element;
    if (!attribute.empty()) s += (element.empty() && !s.empty() ? ": @" : "@") + attribute;
    return s;
  }
};

/// What went wrong, in the terms the runner turns into an exit code.
enum class ErrorKind {
  scene,   ///< the scene files are missing, malformed or physically invalid (exit 2)
  plugin,  ///< a plugin could not be found, loaded or created (exit 3)
  usage,   ///< a bad request from the caller: unknown signal, bad command-line value (exit 4)
  runtime  ///< the simulation failed while running, e.g. a NaN state (exit 5)
};

/// Error with a location; `what()` is the full message "location: message".
class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const Location& where, const std::string& message)
      : std::runtime_error(where.str().empty() ? message : where.str() + ": " + message),
        kind_(kind),
        where_(where),
        message_(message) {}
  Error(ErrorKind kind, const std::string& message) : Error(kind, Location{}, message) {}

  ErrorKind kind() const { return kind_; }
  const Location& where() const { return where_; }
  /// The message without the location.
  const std::string& message() const { return message_; }

 private:
  ErrorKind kind_;
  Location where_;
  std::string message_;
};

}  // namespace s2sim
