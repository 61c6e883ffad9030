#include "corsa/core/diagnostic.h"

#include <sstream>

namespace corsa {

std::string_view severity_name(Severity severity) {
  switch (severity) {
    case Severity::kNote:
      return "note";
    case Severity::kWarning:
      return "warning";
    case Severity::kError:
      return "error";
  }
  return "error";
}

std::string Diagnostic::format() const {
  std::ostringstream out;
  if (!file.empty()) {
    out << file;
    if (line > 0) {
      out << ':' << line;
    }
    out << ": ";
    if (line <= 0 && record >= 0) {
      out << "record " << record << ": ";
    }
  } else if (record >= 0) {
    out << "record " << record << ": ";
  }
  out << severity_name(severity) << ": " << message;
  if (!path.empty()) {
    out << " [in " << path << ']';
  }
  return out.str();
}

std::ostream& operator<<(std::ostream& out, const Diagnostic& diagnostic) {
  return out << diagnostic.format();
}

Diagnostic make_error(std::string file, int line, std::string message, std::string path) {
  return Diagnostic{Severity::kError, std::move(file),   line, -1,
                    std::move(path),  std::move(message)};
}

Diagnostic make_warning(std::string file, int line, std::string message, std::string path) {
  return Diagnostic{Severity::kWarning, std::move(file),   line, -1,
                    std::move(path),    std::move(message)};
}

InputError::InputError(Diagnostic diagnostic)
    : std::runtime_error(diagnostic.format()), diagnostics_{std::move(diagnostic)} {}

namespace {
std::string joined(const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const auto& diagnostic : diagnostics) {
    text += (text.empty() ? "" : "\n") + diagnostic.format();
  }
  return text;
}
}  // namespace

std::string InputError::brief() const {
  std::string text = diagnostics_.front().format();
  if (diagnostics_.size() > 1) {
    text += " (and " + std::to_string(diagnostics_.size() - 1) + " more error" +
            (diagnostics_.size() > 2 ? "s" : "") + ")";
  }
  return text;
}

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(joined(diagnostics)), diagnostics_(std::move(diagnostics)) {}

void Diagnostics::add(Diagnostic diagnostic) {
  std::lock_guard lock(mutex_);
  items_.push_back(std::move(diagnostic));
  if (listener_) {
    listener_(items_.back());
  }
}

bool Diagnostics::add_once(const std::string& key, Diagnostic diagnostic) {
  std::lock_guard lock(mutex_);
  if (!seen_keys_.insert(key).second) {
    return false;
  }
  items_.push_back(std::move(diagnostic));
  if (listener_) {
    listener_(items_.back());
  }
  return true;
}

std::vector<Diagnostic> Diagnostics::all() const {
  std::lock_guard lock(mutex_);
  return items_;
}

size_t Diagnostics::count(Severity severity) const {
  std::lock_guard lock(mutex_);
  size_t n = 0;
  for (const auto& item : items_) {
    n += item.severity == severity ? 1 : 0;
  }
  return n;
}

size_t Diagnostics::size() const {
  std::lock_guard lock(mutex_);
  return items_.size();
}

}  // namespace corsa
