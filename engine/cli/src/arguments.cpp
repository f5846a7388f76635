#include "cli/arguments.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace rumble::cli {

Arguments::Arguments(const std::vector<std::string>& args, const std::set<std::string>& flags,
                     const std::set<std::string>& valued, const std::set<std::string>& repeated) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0 || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    const auto eq = name.find('=');
    const bool has_value = eq != std::string::npos;
    if (has_value) {
      value = name.substr(eq + 1);
      name.resize(eq);
    }
    if (flags.count(name) != 0 && !has_value) {
      flags_.insert(name);
    } else if (valued.count(name) != 0 || repeated.count(name) != 0) {
      if (!has_value) {
        if (i + 1 >= args.size()) throw UsageError("option --" + name + " needs a value");
        value = args[++i];
      }
      if (repeated.count(name) != 0) {
        repeated_[name].push_back(value);
      } else {
        values_[name] = value;
      }
    } else {
      std::string known;
      for (const auto* set : {&flags, &valued, &repeated})
        for (const auto& k : *set) known += (known.empty() ? "--" : ", --") + k;
      throw UsageError("unknown option '" + a + "'" +
                       (known.empty() ? std::string() : "; options here: " + known));
    }
  }
}

std::optional<std::string> Arguments::value(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string Arguments::choice(const std::string& name, const std::vector<std::string>& choices,
                              const std::string& fallback) const {
  const auto v = value(name);
  if (!v) return fallback;
  std::string list;
  for (const auto& c : choices) {
    if (c == *v) return c;
    list += (list.empty() ? "" : ", ") + c;
  }
  throw UsageError("--" + name + "=" + *v + " is not valid; choose one of: " + list);
}

std::optional<std::string> Arguments::directory(const std::string& name,
                                                const std::string& writes) const {
  const auto v = value(name);
  if (!v) return v;
  const std::filesystem::path p(*v);
  const std::string ext = p.extension().string();
  for (const char* file_type : {".csv", ".json", ".vtu", ".pvd", ".png", ".svg", ".txt", ".log"}) {
    if (ext != file_type) continue;
    throw UsageError("--" + name + " " + *v + " names a file; this command writes " + writes +
                     " into the directory --" + name + " names, e.g. --" + name + " " +
                     std::filesystem::path(p).replace_extension().string());
  }
  return v;
}

std::vector<std::string> Arguments::values(const std::string& name) const {
  const auto it = repeated_.find(name);
  return it == repeated_.end() ? std::vector<std::string>{} : it->second;
}

double Arguments::number(const std::string& name, double fallback) const {
  const auto v = value(name);
  if (!v) return fallback;
  char* end = nullptr;
  const double x = std::strtod(v->c_str(), &end);
  if (end == v->c_str() || *end != '\0') {
    throw UsageError("--" + name + "=" + *v + " is not a number");
  }
  return x;
}

long long Arguments::integer(const std::string& name, long long fallback, long long min,
                             long long max) const {
  const auto v = value(name);
  if (!v) return fallback;
  const double x = number(name, 0.0);
  const std::string range =
      "; give a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  if (!(x == std::floor(x)))
    throw UsageError("--" + name + "=" + *v + " is not a whole number" + range);
  if (x < static_cast<double>(min))
    throw UsageError("--" + name + "=" + *v + " is too small" + range);
  if (x > static_cast<double>(max))
    throw UsageError("--" + name + "=" + *v + " is too large" + range);
  return static_cast<long long>(x);
}

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace rumble::cli
