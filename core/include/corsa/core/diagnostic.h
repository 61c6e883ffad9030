#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace corsa {

enum class Severity { kNote, kWarning, kError };

/// Where a problem in an input file is, and what it is.
///
/// Printed as `file:line: error: message` (XML, text), or `file: record N: error: message` for
/// record-based inputs (DBF/Shapefile), with the element path appended when known.
struct Diagnostic {
  Severity severity = Severity::kError;
  std::string file;     ///< input file as the user named it; empty when not from a file
  int line = 0;         ///< 1-based line, 0 when unknown
  int64_t record = -1;  ///< 0-based record number for DBF/Shapefile inputs, -1 when not applicable
  std::string path;     ///< element path, e.g. "OpenSCENARIO/Storyboard/Init"; may be empty
  std::string message;

  /// The one-line form users and tests read: `file:line: error: message [in path]`.
  std::string format() const;
};

std::string_view severity_name(Severity severity);
std::ostream& operator<<(std::ostream& out, const Diagnostic& diagnostic);

/// Convenience constructors.
Diagnostic make_error(std::string file, int line, std::string message, std::string path = {});
Diagnostic make_warning(std::string file, int line, std::string message, std::string path = {});

/// Thrown for bad input (never for our own bugs). Carries the located diagnostic; what() is the
/// formatted line so that an uncaught one still says where the problem is. A loader that reports
/// every error of a file in one pass throws one InputError holding all of them, in the order
/// found: diagnostic() is the first, diagnostics() all, and what() their lines joined by '\n'.
class InputError : public std::runtime_error {
 public:
  explicit InputError(Diagnostic diagnostic);
  /// `diagnostics` must not be empty.
  explicit InputError(std::vector<Diagnostic> diagnostics);
  const Diagnostic& diagnostic() const { return diagnostics_.front(); }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  /// One line: the first diagnostic, with "(and N more errors)" when there are others.
  std::string brief() const;

 private:
  std::vector<Diagnostic> diagnostics_;
};

/// Collects the warnings (and non-fatal errors) of one load or run. Not global: every loader and
/// simulation owns or is handed one. `warn_once` reports a given key only the first time, e.g. one
/// warning per unknown element name rather than one per occurrence. Thread-safe.
class Diagnostics {
 public:
  /// Called for each diagnostic as it is added (e.g. to print it at once); optional.
  using Listener = std::function<void(const Diagnostic&)>;

  Diagnostics() = default;
  explicit Diagnostics(Listener listener) : listener_(std::move(listener)) {}
  Diagnostics(const Diagnostics&) = delete;
  Diagnostics& operator=(const Diagnostics&) = delete;

  void add(Diagnostic diagnostic);
  /// Adds the diagnostic unless one with the same key was added before; returns whether it was.
  bool add_once(const std::string& key, Diagnostic diagnostic);

  std::vector<Diagnostic> all() const;
  size_t count(Severity severity) const;
  size_t size() const;
  bool has_errors() const { return count(Severity::kError) > 0; }

 private:
  mutable std::mutex mutex_;
  std::vector<Diagnostic> items_;
  std::set<std::string> seen_keys_;
  Listener listener_;
};

}  // namespace corsa
