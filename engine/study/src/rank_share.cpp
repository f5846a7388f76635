#include "study/rank_share.hpp"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <iostream>

#include "core/cpu_affinity.hpp"
#include "core/interrupt.hpp"
#include "parallel/mirror_transport.hpp"
#include "parallel/mpi_session.hpp"
#include "plugin/mirror_message.hpp"

namespace rumble::study {
namespace {

std::string host_name() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string("?");
}

/// Rank 0's message: the jobs asked for, then per run given away its record's index, rank,
/// name, results directory and command.
std::vector<char> share_message(const std::vector<RunRecord>& records,
                                const std::vector<int>& rank_of, int jobs_given) {
  mirror::Writer w;
  w.put(mirror::Service::kStudy).put(jobs_given);
  std::uint64_t n = 0;
  for (int r : rank_of) n += r > 0 ? 1 : 0;
  w.put(n);
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (rank_of[i] <= 0) continue;
    w.put(static_cast<std::uint64_t>(i)).put(rank_of[i]);
    w.put_text(records[i].run.name).put_text(records[i].results.string());
    w.put(static_cast<std::uint64_t>(records[i].command.size()));
    for (const std::string& a : records[i].command) w.put_text(a);
  }
  return w.bytes();
}

/// What became of one run, for rank 0.
void put_outcome(mirror::Writer& w, std::uint64_t index, const RunRecord& r) {
  w.put(index).put(static_cast<int>(r.state)).put(r.exit_code.has_value());
  w.put(r.exit_code.value_or(0)).put(r.wall_time_s.has_value()).put(r.wall_time_s.value_or(0.0));
  w.put_text(r.message);
}

void take_outcomes(const std::vector<char>& bytes, int rank, std::vector<RunRecord>& records) {
  if (bytes.empty()) return;
  mirror::Reader r(bytes);
  const std::string host = r.get_text();
  const auto n = r.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < n; ++k) {
    RunRecord& record = records.at(static_cast<std::size_t>(r.get<std::uint64_t>()));
    record.state = static_cast<RunState>(r.get<int>());
    const bool has_code = r.get<bool>();
    const int code = r.get<int>();
    record.exit_code = has_code ? std::optional<int>(code) : std::nullopt;
    const bool has_wall = r.get<bool>();
    const double wall = r.get<double>();
    record.wall_time_s = has_wall ? std::optional<double>(wall) : std::nullopt;
    record.message = r.get_text();
    record.rank = rank;
    record.host = host;
  }
}

}  // namespace

bool run_over_ranks(std::vector<RunRecord>& records, const RunnerOptions& options, int jobs_given,
                    const std::function<void()>& on_change) {
  const int size = parallel::world_size();
  std::vector<int> rank_of(records.size(), -1);
  int k = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].state != RunState::kPending) continue;
    rank_of[i] = k++ % size;
    if (rank_of[i] > 0) records[i].state = RunState::kRunning;  // elsewhere, from now on
    records[i].rank = rank_of[i];
    records[i].host = rank_of[i] == 0 ? host_name() : "";
  }
  parallel::send_to_servers(share_message(records, rank_of, jobs_given));
  on_change();
  const bool whole = run_pending(records, options, on_change);
  const std::vector<std::vector<char>> outcomes = parallel::gather_to_root({});
  for (std::size_t rank = 1; rank < outcomes.size(); ++rank)
    take_outcomes(outcomes[rank], static_cast<int>(rank), records);
  const bool interrupted_elsewhere =
      std::any_of(records.begin(), records.end(),
                  [](const RunRecord& r) { return r.state == RunState::kInterrupted; });
  return whole && !interrupted_elsewhere;
}

void run_share(const std::vector<char>& message) {
  mirror::Reader r(message);
  r.get<mirror::Service>();
  const int jobs_given = r.get<int>();
  const auto n = r.get<std::uint64_t>();
  const int rank = parallel::world_rank();
  std::vector<RunRecord> mine;
  std::vector<std::uint64_t> index;
  for (std::uint64_t k = 0; k < n; ++k) {
    const auto i = r.get<std::uint64_t>();
    const int to = r.get<int>();
    RunRecord record;
    record.run.name = r.get_text();
    record.results = r.get_text();
    record.command.resize(static_cast<std::size_t>(r.get<std::uint64_t>()));
    for (std::string& a : record.command) a = r.get_text();
    if (to != rank) continue;
    mine.push_back(std::move(record));
    index.push_back(i);
  }
  RunnerOptions options;
  options.executable = std::filesystem::read_symlink("/proc/self/exe");
  options.jobs = jobs_given > 0 ? jobs_given : std::max(1, usable_cpus() / 2);
  options.progress = &std::cerr;
  // mpirun turns Ctrl-C into SIGTERM on every rank: this rank's runs stop as rank 0's do.
  install_interrupt_handler(4.0 * kStopGraceSeconds);
  run_pending(mine, options, [] {});
  std::signal(SIGINT, SIG_IGN);  // back to a server's: rank 0 alone decides
  std::signal(SIGTERM, SIG_IGN);
  mirror::Writer w;
  w.put_text(host_name()).put(static_cast<std::uint64_t>(mine.size()));
  for (std::size_t k = 0; k < mine.size(); ++k) put_outcome(w, index[k], mine[k]);
  parallel::gather_to_root(w.bytes());
}

}  // namespace rumble::study
