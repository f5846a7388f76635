#include "run/summary_writer.hpp"

#include "plugin/registry.hpp"
#include "run/new_file.hpp"
#include "run/results_directory.hpp"
#include "run/run_components.hpp"

namespace rumble {

namespace fs = std::filesystem;

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::kRunning:
      return "running";
    case RunStatus::kCompleted:
      return "completed";
    case RunStatus::kInterrupted:
      return "interrupted";
    case RunStatus::kFailed:
      return "failed";
  }
  return "failed";
}

int exit_code(RunStatus status) {
  return status == RunStatus::kCompleted ? 0 : 3;
}

SummaryWriter::SummaryWriter(ResultsDirectory& results, const scenario::RunSpec& spec,
                             const RunComponents& components)
    : path_(results.file("summary.json")), tmp_(results.file("summary.json.tmp")) {
  summary_["rumble_version"] = RUMBLE_VERSION;
  summary_["scenario_file"] = fs::absolute(spec.path).string();
  summary_["scenario"] = spec.document;
  summary_["status"] = status_name(RunStatus::kRunning);
  nlohmann::json plugins = nlohmann::json::array();
  for (const Instance* inst : components.instances()) {
    const auto* d = inst->type().library->descriptor;
    plugins.push_back({{"type", inst->type_name()},
                       {"kind", kind_name(inst->type().kind)},
                       {"at", inst->label()},
                       {"plugin", d->plugin_name},
                       {"version", d->plugin_version},
                       {"abi", std::to_string(d->abi_major) + "." + std::to_string(d->abi_minor)},
                       {"path", inst->type().library->path.string()}});
  }
  summary_["plugins"] = plugins;
  write();
}

void SummaryWriter::finish(RunStatus status, const std::string& message) {
  summary_["status"] = status_name(status);
  if (!message.empty()) summary_["message"] = message;
  write();
}

void SummaryWriter::fail(const std::string& message) noexcept {
  try {
    summary_["status"] = status_name(RunStatus::kFailed);
    summary_["message"] = message;
    write();
  } catch (...) {
    // The disk refused the summary too; the caller reports the original error.
  }
}

void SummaryWriter::write() const {
  replace_file(path_, tmp_, summary_.dump(2) + '\n');
}

}  // namespace rumble
