// Minimal command-line parsing: positional arguments and --name[=value] / --name value options,
// with errors that name the offending argument and the valid choices.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble::cli {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Arguments {
 public:
  /// flags: options without a value; valued: options that take one (the last one given
  /// counts); repeated: options that take one and may be given any number of times.
  Arguments(const std::vector<std::string>& args, const std::set<std::string>& flags,
            const std::set<std::string>& valued, const std::set<std::string>& repeated = {});
  const std::vector<std::string>& positional() const { return positional_; }
  bool flag(const std::string& name) const { return flags_.count(name) != 0; }
  std::optional<std::string> value(const std::string& name) const;
  /// The value, which must be one of choices.
  std::string choice(const std::string& name, const std::vector<std::string>& choices,
                     const std::string& fallback) const;
  double number(const std::string& name, double fallback) const;
  /// The value as a whole number from min to max; "2.5" or "1e9" beyond max is refused with the
  /// range (a count cast from a double silently became 2, or overflowed an int).
  long long integer(const std::string& name, long long fallback, long long min,
                    long long max) const;
  /// The value of an option that names a directory, refused when it looks like a file name
  /// (x.csv, x.json, x.vtu, x.png ...), which would otherwise become a folder of that name;
  /// `writes`: what the command puts there, for the message ("one CSV per scenario").
  std::optional<std::string> directory(const std::string& name, const std::string& writes) const;
  /// Every value of a repeated option, in command-line order.
  std::vector<std::string> values(const std::string& name) const;

 private:
  std::vector<std::string> positional_;
  std::set<std::string> flags_;
  std::map<std::string, std::string> values_;
  std::map<std::string, std::vector<std::string>> repeated_;
};

/// The items of a comma-separated list ("a,b,,c" -> a, b, c): empty items are dropped.
std::vector<std::string> split_list(const std::string& list);

}  // namespace rumble::cli
