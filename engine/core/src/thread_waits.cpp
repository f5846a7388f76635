#include "core/thread_waits.hpp"

#include <cstdlib>

namespace rumble {

bool prefer_passive_thread_waits() {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr)
    return false;
  return ::setenv("OMP_WAIT_POLICY", "PASSIVE", 0) == 0;
}

}  // namespace rumble
