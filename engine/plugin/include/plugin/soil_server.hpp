// Ranks other than 0 of an MPI launch (docs/decisions/0012-distributed-soil.md §1): each holds a
// copy of every distributed soil rank 0 creates, and makes on it every call rank 0 makes, with
// the same inputs, so that the soil's own collective operations meet. What those calls return is
// rank 0's; a server's outputs are dropped. An error is sent back to rank 0, which stops the run
// with it. The loop that receives the messages is the command line's (cli/serve.hpp).
#pragma once

#include <cstdint>
#include <map>
#include <memory>

#include "plugin/instance.hpp"
#include "plugin/mirror_message.hpp"
#include "plugin/registry.hpp"

namespace rumble {

/// This rank's copies of rank 0's distributed soils, by the id rank 0 gave each.
class SoilServer {
 public:
  /// Makes the call a soil message asks for (read past its Service byte) on this rank's copy,
  /// then tells rank 0 how it went (collective: parallel::first_failure).
  void serve(mirror::Reader& message);

 private:
  void make(mirror::Call call, std::uint64_t id, mirror::Reader& r);
  void create(mirror::Reader& r, std::uint64_t id);
  SoilInstance& at(std::uint64_t id);
  PluginRegistry registry_;
  std::map<std::uint64_t, std::unique_ptr<SoilInstance>> soils_;
};

}  // namespace rumble
