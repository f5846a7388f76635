#include "run/crash_record.hpp"

#include <signal.h>

#include <array>
#include <atomic>
#include <csignal>
#include <vector>

#include "run/summary_writer.hpp"

namespace rumble {
namespace {

constexpr std::array<int, 5> kCrashSignals = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

std::atomic<SummaryWriter*> g_summary{nullptr};
thread_local const char* t_participant = nullptr;

void on_crash(int sig) {
  // One record: a second crash (another thread, or inside this handler) finds none to write.
  if (SummaryWriter* summary = g_summary.exchange(nullptr))
    summary->crashed(sig, t_participant != nullptr ? t_participant : "the engine");
  // SA_RESETHAND gave the signal back its default action: end as it would have ended.
  ::raise(sig);
}

/// The alternate stack the handler runs on (a stack overflow leaves none on the thread's own).
std::vector<char>& alternate_stack() {
  static std::vector<char> stack(std::size_t{1} << 16);
  return stack;
}

}  // namespace

CrashRecord::CrashRecord(SummaryWriter& summary) {
  std::vector<char>& stack = alternate_stack();
  stack_t ss{};
  ss.ss_sp = stack.data();
  ss.ss_size = stack.size();
  ::sigaltstack(&ss, nullptr);  // where refused, the handler runs on the thread's stack
  struct sigaction action {};
  action.sa_handler = on_crash;
  action.sa_flags = SA_RESETHAND | SA_NODEFER | SA_ONSTACK;
  ::sigemptyset(&action.sa_mask);
  g_summary = &summary;
  for (const int s : kCrashSignals) ::sigaction(s, &action, nullptr);
}

CrashRecord::~CrashRecord() {
  g_summary = nullptr;
  for (const int s : kCrashSignals) ::signal(s, SIG_DFL);
}

SteppingParticipant::SteppingParticipant(const char* participant) noexcept
    : previous_(t_participant) {
  t_participant = participant;
}

SteppingParticipant::~SteppingParticipant() {
  t_participant = previous_;
}

}  // namespace rumble
