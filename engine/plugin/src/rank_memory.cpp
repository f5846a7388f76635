#include "plugin/rank_memory.hpp"

#include "core/malloc_policy.hpp"
#include "core/peak_memory.hpp"
#include "parallel/mirror_transport.hpp"
#include "parallel/mpi_session.hpp"
#include "plugin/mirror_message.hpp"

namespace rumble {

std::optional<ServerPeaks> end_phase_on_servers() {
  if (!parallel::running() || parallel::world_size() < 2 || parallel::world_rank() != 0)
    return std::nullopt;
  mirror::Writer w;
  w.put(mirror::Service::kPhaseEnd);
  parallel::send_to_servers(w.bytes());
  const std::vector<std::vector<char>> each = parallel::gather_to_root({});
  ServerPeaks peaks;
  for (std::size_t rank = 1; rank < each.size(); ++rank) {
    mirror::Reader r(each[rank]);
    peaks.bytes.push_back(r.get<std::uint64_t>());
    peaks.separate = r.get<bool>() && peaks.separate;
  }
  return peaks;
}

void answer_phase_end() {
  const std::uint64_t peak = peak_resident_bytes();
  trim_freed_memory();  // the next phase starts from what is in use, as on rank 0
  const bool restarted = restart_peak_resident();
  mirror::Writer w;
  w.put(peak).put(restarted);
  parallel::gather_to_root(w.bytes());
}

}  // namespace rumble
