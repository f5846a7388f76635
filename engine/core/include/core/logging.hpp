// Logging: one spdlog logger per component ("engine", "track", "soil/winkler" ...), all writing to
// stderr through one shared sink, so that plugin messages and engine messages interleave in order.
#pragma once

#include <spdlog/spdlog.h>

#include <memory>
#include <string>

namespace rumble {

/// The logger for a component, created on first use with the current global level.
std::shared_ptr<spdlog::logger> logger(const std::string& component);

/// "trace", "debug", "info", "warn", "error", "off"; false if the name is unknown.
bool set_log_level(const std::string& level);

}  // namespace rumble
