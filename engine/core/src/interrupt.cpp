#include "core/interrupt.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

namespace rumble {
namespace {

std::atomic<int> g_interrupts{0};
std::atomic<int> g_first_signal{0};  // the signal that asked first (0: a request in code)

// The deadline: the handler writes a byte to a pipe (async-signal-safe), the watchdog thread
// waits on it, then gives the process its grace.
int g_wake[2] = {-1, -1};
std::atomic<double> g_grace_s{kStopGraceSeconds};
std::atomic<const char*> g_phase{"the run"};
std::mutex g_word_mutex;
LastWord g_last_word;  // guarded by g_word_mutex

extern "C" void on_signal(int signal) {
  int none = 0;
  g_first_signal.compare_exchange_strong(none, signal);
  if (g_interrupts.fetch_add(1) >= 1) std::_Exit(130);  // second Ctrl-C: stop now
  const int saved = errno;
  if (g_wake[1] >= 0) (void)!::write(g_wake[1], "x", 1);
  errno = saved;
}

void watch_the_deadline() {
  char byte = 0;
  for (;;) {
    const ssize_t n = ::read(g_wake[0], &byte, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    std::this_thread::sleep_for(std::chrono::duration<double>(g_grace_s.load()));
    if (!interrupt_requested()) continue;  // cleared (a study's loop, a test): not ours to end
    const char* phase = g_phase.load();
    std::fprintf(stderr,
                 "rumble: error: stopped by %s: %s did not stop within %.1f s of the request, so "
                 "the process ends here; what was finished is on disk\n",
                 interrupt_cause(), phase, g_grace_s.load());
    int code = 130;
    {
      const std::lock_guard lock(g_word_mutex);
      if (g_last_word) code = g_last_word(phase);
    }
    std::fflush(stderr);
    std::_Exit(code);
  }
}

}  // namespace

void install_interrupt_handler(double grace_s) {
  g_grace_s = grace_s;
  static std::once_flag once;
  std::call_once(once, [] {
    if (::pipe2(g_wake, O_CLOEXEC) == 0) {
      ::fcntl(g_wake[1], F_SETFL, O_NONBLOCK);  // a handler never blocks on a full pipe
      std::thread(watch_the_deadline).detach();
    }
  });
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}
bool interrupt_requested() {
  return g_interrupts.load() > 0;
}
void request_interrupt() {
  g_interrupts.fetch_add(1);
}
void clear_interrupt() {
  g_interrupts.store(0);
  g_first_signal.store(0);
}
const char* interrupt_cause() {
  return g_first_signal.load() == SIGTERM ? "SIGTERM" : "Ctrl-C";
}

LastWordScope::LastWordScope(LastWord word) {
  const std::lock_guard lock(g_word_mutex);
  g_last_word = std::move(word);
}
LastWordScope::~LastWordScope() {
  const std::lock_guard lock(g_word_mutex);
  g_last_word = nullptr;
}

StopPhase::StopPhase(const char* phase) noexcept : previous_(g_phase.exchange(phase)) {}
StopPhase::~StopPhase() {
  g_phase = previous_;
}

}  // namespace rumble
