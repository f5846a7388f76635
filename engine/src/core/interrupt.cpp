#include "core/interrupt.hpp"

#include <atomic>
#include <csignal>
#include <cstdlib>

namespace rumble {
namespace {

std::atomic<int> g_interrupts{0};
std::atomic<int> g_first_signal{0};  // the signal that asked first (0: a request in code)

extern "C" void on_signal(int signal) {
  int none = 0;
  g_first_signal.compare_exchange_strong(none, signal);
  if (g_interrupts.fetch_add(1) >= 1) std::_Exit(130);  // second Ctrl-C: stop now
}

}  // namespace

void install_interrupt_handler() {
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

}  // namespace rumble
