#include "cli/rank_server.hpp"

#include <csignal>
#include <optional>
#include <vector>

#include "parallel/mirror_transport.hpp"
#include "plugin/mirror_message.hpp"
#include "plugin/rank_memory.hpp"
#include "plugin/soil_server.hpp"
#include "study/rank_share.hpp"

namespace rumble::cli {

void serve_rank_zero() {
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_IGN);
  SoilServer soils;
  while (const std::optional<std::vector<char>> message = parallel::next_from_root()) {
    mirror::Reader r(*message);
    const mirror::Service service = r.get<mirror::Service>();
    if (service == mirror::Service::kSoil) {
      soils.serve(r);
    } else if (service == mirror::Service::kPhaseEnd) {
      answer_phase_end();
    } else {
      study::run_share(*message);
    }
  }
}

}  // namespace rumble::cli
