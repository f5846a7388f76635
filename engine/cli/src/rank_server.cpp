#include "cli/rank_server.hpp"

#include <csignal>
#include <optional>
#include <vector>

#include "parallel/mirror_transport.hpp"
#include "plugin/mirror_message.hpp"
#include "plugin/soil_server.hpp"
#include "study/rank_share.hpp"

namespace rumble::cli {

void serve_rank_zero() {
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_IGN);
  SoilServer soils;
  while (const std::optional<std::vector<char>> message = parallel::next_from_root()) {
    mirror::Reader r(*message);
    if (r.get<mirror::Service>() == mirror::Service::kSoil) {
      soils.serve(r);
    } else {
      study::run_share(*message);
    }
  }
}

}  // namespace rumble::cli
