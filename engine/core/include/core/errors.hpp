// Engine-side exception types. Each maps to one CLI exit code (see cli/exit_codes.hpp).
#pragma once

#include <stdexcept>
#include <string>

namespace rumble {

/// The scenario is wrong (exit code 1). Diagnostics are printed before this is thrown.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A plugin library could not be loaded or registered (exit code 2).
class PluginLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The run failed after it started: plugin ERROR, divergence, I/O, interrupt (exit code 3).
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rumble

namespace rumble {

/// The user interrupted the run (Ctrl-C / SIGTERM); results so far are kept.
class Interrupted : public RunError {
 public:
  using RunError::RunError;
};

}  // namespace rumble
