#pragma once

#include <optional>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace corsa::cli {

/// Wrong command-line usage (unknown option, missing value, bad number). Exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The options and positionals a subcommand accepts; also renders its --help.
class ArgParser;

/// Parsed command line of one subcommand.
class ParsedArgs {
 public:
  bool help() const { return help_; }
  bool flag(const std::string& name) const;
  std::optional<std::string> value(const std::string& name) const;
  std::string value_or(const std::string& name, const std::string& fallback) const;
  /// Every value of a repeatable option, in command-line order.
  std::vector<std::string> values(const std::string& name) const;
  /// Every value of a repeatable NAME=VALUE option (--param), split at the first '=', in
  /// command-line order; throws UsageError naming the option for a value without a NAME=.
  std::vector<std::pair<std::string, std::string>> assignments(const std::string& name) const;
  /// A numeric option; throws UsageError naming the option when the text is not a number.
  std::optional<double> number(const std::string& name) const;
  std::optional<long long> integer(const std::string& name) const;
  /// An option whose value must be one of `names`; throws UsageError "NAME expects a, b or c,
  /// got 'x'" (with the nearest name, when one is near) for any other text.
  std::optional<std::string> choice(const std::string& name,
                                    const std::vector<std::string>& names) const;
  const std::vector<std::string>& positionals() const { return positionals_; }

 private:
  friend class ArgParser;
  bool help_ = false;
  std::vector<std::pair<std::string, std::string>> options_;  // name -> value ("" for flags)
  std::vector<std::string> positionals_;
};

class ArgParser {
 public:
  /// `usage` is the synopsis after "corsa", e.g. "run SCENARIO.xosc [options]".
  ArgParser(std::string usage, std::string summary);

  ArgParser& flag(std::string name, std::string help);
  ArgParser& option(std::string name, std::string value_name, std::string help);
  ArgParser& repeated(std::string name, std::string value_name, std::string help);
  /// Positional arguments: `min`..`max` of them (max < 0: unlimited).
  ArgParser& positional(std::string name, std::string help, int min = 1, int max = 1);
  /// Free text appended to --help (examples, notes).
  ArgParser& epilog(std::string text);
  /// Options declared after this are listed in --help under `title` (e.g. "dataset options").
  ArgParser& section(std::string title);

  /// Parses `args` (without the program and subcommand names). --help / -h anywhere sets help().
  ParsedArgs parse(std::span<const std::string> args) const;
  void print_help(std::ostream& out) const;

 private:
  struct Option {
    std::string name;
    std::string value_name;  // empty for flags
    std::string help;
    bool repeated = false;
    std::string section;  // --help heading; empty: "options"
  };
  const Option* find(const std::string& name) const;

  std::string usage_;
  std::string summary_;
  std::string epilog_;
  std::vector<Option> options_;
  std::string section_;
  std::string positional_name_;
  std::string positional_help_;
  int positional_min_ = 0;
  int positional_max_ = 0;
};

}  // namespace corsa::cli
