// The messages between rank 0 and the other ranks of a launch (decision 0012,
// docs/decisions/0012-distributed-soil.md): rank 0 sends each call of a distributed soil (or a
// study's runs) to the other ranks, and what each did comes back to rank 0. Bytes only: what a
// message means is its sender's (plugin/mirror_message.hpp, the study's share). Every function is
// collective over MPI_COMM_WORLD.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace rumble::parallel {

/// Rank 0: sends one message to every other rank.
void send_to_servers(const std::vector<char>& message);

/// Rank 0, once, from finish(): ends every server's loop (next_from_root gives nothing).
void release_servers();

/// Ranks other than 0: the next message from rank 0; nothing when rank 0 released the servers
/// (its finish()). Waits without spinning for long: a server polls, sleeping up to 1 ms between
/// polls once nothing came for a while, so that it leaves rank 0 its core.
std::optional<std::vector<char>> next_from_root();

/// Every rank sends its bytes; rank 0 gets every rank's, in rank order (its own first), the
/// others nothing.
std::vector<std::vector<char>> gather_to_root(const std::vector<char>& mine);

/// Every rank: its error of the call just made ("" for none). Rank 0 gets the first failing
/// rank's error, "rank k: ..." (its own first), or "" when every rank succeeded; the others "".
std::string first_failure(const std::string& mine);

}  // namespace rumble::parallel
