#include "args.h"

#include <algorithm>
#include <iomanip>

#include "corsa/core/strings.h"

namespace corsa::cli {

bool ParsedArgs::flag(const std::string& name) const {
  for (const auto& [key, value] : options_) {
    if (key == name) {
      return true;
    }
  }
  return false;
}

std::optional<std::string> ParsedArgs::value(const std::string& name) const {
  std::optional<std::string> last;
  for (const auto& [key, value] : options_) {
    if (key == name) {
      last = value;
    }
  }
  return last;
}

std::string ParsedArgs::value_or(const std::string& name, const std::string& fallback) const {
  return value(name).value_or(fallback);
}

std::vector<std::string> ParsedArgs::values(const std::string& name) const {
  std::vector<std::string> all;
  for (const auto& [key, value] : options_) {
    if (key == name) {
      all.push_back(value);
    }
  }
  return all;
}

std::vector<std::pair<std::string, std::string>> ParsedArgs::assignments(
    const std::string& name) const {
  std::vector<std::pair<std::string, std::string>> all;
  for (const std::string& assignment : values(name)) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw UsageError(name + " expects NAME=VALUE, got '" + assignment + "'");
    }
    all.emplace_back(assignment.substr(0, eq), assignment.substr(eq + 1));
  }
  return all;
}

std::optional<double> ParsedArgs::number(const std::string& name) const {
  const auto text = value(name);
  if (!text) {
    return std::nullopt;
  }
  const auto parsed = parse_double(*text);
  if (!parsed) {
    throw UsageError(name + " expects a number, got '" + *text + "'");
  }
  return parsed;
}

std::optional<long long> ParsedArgs::integer(const std::string& name) const {
  const auto text = value(name);
  if (!text) {
    return std::nullopt;
  }
  const auto parsed = parse_int(*text);
  if (!parsed) {
    throw UsageError(name + " expects an integer, got '" + *text + "'");
  }
  return *parsed;
}

std::optional<std::string> ParsedArgs::choice(const std::string& name,
                                              const std::vector<std::string>& names) const {
  auto text = value(name);
  if (!text || std::find(names.begin(), names.end(), *text) != names.end()) {
    return text;
  }
  std::string listed;
  for (size_t i = 0; i < names.size(); ++i) {
    listed += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  throw UsageError(name + " expects " + listed + ", got '" + *text + "'" +
                   did_you_mean(*text, names));
}

ArgParser::ArgParser(std::string usage, std::string summary)
    : usage_(std::move(usage)), summary_(std::move(summary)) {}

ArgParser& ArgParser::flag(std::string name, std::string help) {
  options_.push_back({std::move(name), "", std::move(help), false, section_});
  return *this;
}

ArgParser& ArgParser::option(std::string name, std::string value_name, std::string help) {
  options_.push_back({std::move(name), std::move(value_name), std::move(help), false, section_});
  return *this;
}

ArgParser& ArgParser::repeated(std::string name, std::string value_name, std::string help) {
  options_.push_back({std::move(name), std::move(value_name), std::move(help), true, section_});
  return *this;
}

ArgParser& ArgParser::positional(std::string name, std::string help, int min, int max) {
  positional_name_ = std::move(name);
  positional_help_ = std::move(help);
  positional_min_ = min;
  positional_max_ = max;
  return *this;
}

ArgParser& ArgParser::section(std::string title) {
  section_ = std::move(title);
  return *this;
}

ArgParser& ArgParser::epilog(std::string text) {
  epilog_ = std::move(text);
  return *this;
}

const ArgParser::Option* ArgParser::find(const std::string& name) const {
  for (const auto& option : options_) {
    if (option.name == name) {
      return &option;
    }
  }
  return nullptr;
}

ParsedArgs ArgParser::parse(std::span<const std::string> args) const {
  ParsedArgs parsed;
  bool only_positionals = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (only_positionals || arg.size() < 2 || arg[0] != '-' || parse_double(arg)) {
      parsed.positionals_.push_back(arg);
      continue;
    }
    if (arg == "--") {
      only_positionals = true;
      continue;
    }
    if (arg == "--help" || arg == "-h") {
      parsed.help_ = true;
      continue;
    }
    std::string name = arg;
    std::optional<std::string> inline_value;
    if (const size_t eq = arg.find('='); eq != std::string::npos) {
      name = arg.substr(0, eq);
      inline_value = arg.substr(eq + 1);
    }
    const Option* option = find(name);
    if (option == nullptr) {
      std::vector<std::string> names;
      for (const Option& o : options_) {
        names.push_back(o.name);
      }
      throw UsageError("unknown option '" + name + "'" + did_you_mean(name, names));
    }
    if (option->value_name.empty()) {
      if (inline_value) {
        throw UsageError("option '" + name + "' takes no value");
      }
      parsed.options_.emplace_back(name, "");
      continue;
    }
    if (!inline_value) {
      if (i + 1 >= args.size()) {
        throw UsageError("option '" + name + "' needs a value (" + option->value_name + ")");
      }
      inline_value = args[++i];
    }
    if (!option->repeated && parsed.value(name)) {
      throw UsageError("option '" + name + "' given twice");
    }
    parsed.options_.emplace_back(name, *inline_value);
  }
  if (parsed.help_) {
    return parsed;
  }
  const int count = static_cast<int>(parsed.positionals_.size());
  if (count < positional_min_) {
    throw UsageError(positional_name_.empty() ? "missing argument" : "missing " + positional_name_);
  }
  if (positional_max_ >= 0 && count > positional_max_) {
    throw UsageError("unexpected argument '" + parsed.positionals_[positional_max_] + "'");
  }
  return parsed;
}

void ArgParser::print_help(std::ostream& out) const {
  out << "usage: corsa " << usage_ << "\n\n" << summary_ << "\n";
  if (!positional_name_.empty()) {
    out << "\narguments:\n  " << std::left << std::setw(24) << positional_name_ << ' '
        << positional_help_ << '\n';
  }
  out << "\noptions:\n";
  out << "  " << std::left << std::setw(24) << "-h, --help" << ' ' << "show this help\n";
  std::string section;
  for (const auto& option : options_) {
    if (option.section != section) {
      section = option.section;
      out << '\n' << (section.empty() ? std::string("options") : section) << ":\n";
    }
    std::string left = option.name;
    if (!option.value_name.empty()) {
      left += ' ' + option.value_name;
    }
    if (option.repeated) {
      left += " ...";
    }
    out << "  " << std::left << std::setw(24) << left << ' ' << option.help << '\n';
  }
  if (!epilog_.empty()) {
    out << '\n' << epilog_ << '\n';
  }
}

}  // namespace corsa::cli
