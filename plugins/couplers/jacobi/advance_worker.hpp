// A persistent thread that advances one participant when asked, so that a parallel scheme starts
// no thread per macro step (starting one costs tens of microseconds and allocates its stack:
// comparable to a reduced soil's whole step). One request at a time: start(), then wait().
//
// The handoff is one atomic word. Whoever waits on it (the worker for the next request, the
// coupler for the step's end) first spins on it for a short while, then sleeps on it
// (std::atomic::wait: a futex on Linux). Waking a sleeping thread goes through the kernel and,
// on a virtual machine, the hypervisor: docs/couplers.md ("What the couplers cost") has the
// measured cost per handoff. A spinning thread holds its core, which on a busy machine another
// process or the thread being waited for may need (docs/toolchain.md section 8), so the spin is
// bounded: by kSpinShare of the last request's work (spinning then costs little of the step)
// and by kLongestSpin; and a waiter spins only when its last wait ended within that bound. Where
// waits are long (the two sides' work unlike, or the machine busy: a thread of ours waiting for
// a core) it then sleeps at once, and at most one spin in a row is wasted.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <rumble/plugin.hpp>
#include <thread>

namespace rumble_jacobi {

class AdvanceWorker {
 public:
  /// The longest spin before sleeping [ns], and the spin's largest share of the last request's
  /// wall time [-] (docs/couplers.md, "What the couplers cost").
  static constexpr std::int64_t kLongestSpin = 50'000;
  static constexpr double kSpinShare = 0.05;

  /// `longest_spin` [ns]: kLongestSpin, or 0 for no spin (bench/coupling/handoff_bench.cpp
  /// compares the two).
  AdvanceWorker(const rumble::CosimHost& host, std::uint32_t participant,
                std::int64_t longest_spin = kLongestSpin)
      : host_(host),
        participant_(participant),
        longest_spin_(longest_spin),
        thread_([this] { loop(); }) {}
  AdvanceWorker(const AdvanceWorker&) = delete;
  AdvanceWorker& operator=(const AdvanceWorker&) = delete;
  ~AdvanceWorker() {
    // A request still running (its waiter left by an exception) ends first: its end would
    // overwrite the stop.
    if (state_.load(std::memory_order_acquire) == kRequested)
      await([](std::uint32_t s) { return s == kDone; }, done_wait_);
    state_.store(kStopping, std::memory_order_release);
    state_.notify_one();
    thread_.join();
  }

  /// The participant starts advancing over [t, t + h] on the worker thread, saved in checkpoint
  /// `slot` first when `save` (so that the copy of a large state runs beside the other side's
  /// work rather than before it).
  void start(double t, double h, bool save = false, std::uint32_t slot = 0) {
    t_ = t;
    h_ = h;
    save_ = save;
    slot_ = slot;
    error_ = nullptr;
    state_.store(kRequested, std::memory_order_release);  // publishes the request's fields
    state_.notify_one();
  }

  /// Waits for the step started last; returns its status or rethrows what it threw.
  rumble_status wait() {
    await([](std::uint32_t s) { return s == kDone; }, done_wait_);
    state_.store(kIdle, std::memory_order_relaxed);
    if (error_) std::rethrow_exception(error_);
    return status_;
  }

 private:
  enum : std::uint32_t { kIdle, kRequested, kDone, kStopping };
  using Clock = std::chrono::steady_clock;

  void loop() {
    for (;;) {
      if (await([](std::uint32_t s) { return s == kRequested || s == kStopping; }, request_wait_) ==
          kStopping)
        return;
      const auto begin = Clock::now();
      status_ = RUMBLE_OK;
      try {
        if (save_) host_.save(participant_, slot_);
        status_ = host_.advance(participant_, t_, h_);
      } catch (...) {
        error_ = std::current_exception();
      }
      const auto work =
          std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - begin).count();
      spin_ns_.store(std::min(longest_spin_, static_cast<std::int64_t>(kSpinShare * work)),
                     std::memory_order_relaxed);
      state_.store(kDone, std::memory_order_release);  // publishes the status and the error
      state_.notify_one();
    }
  }

  /// The state once ready(state): spins while the spin is worth it, then sleeps until it
  /// changes. `last`: how long this waiter's previous wait took, updated.
  template <class Ready>
  std::uint32_t await(Ready ready, Clock::duration& last) {
    const auto begin = Clock::now();
    const std::chrono::nanoseconds spin(spin_ns_.load(std::memory_order_relaxed));
    std::uint32_t s = state_.load(std::memory_order_acquire);
    if (last <= spin) {
      for (unsigned i = 1; !ready(s); ++i, s = state_.load(std::memory_order_acquire)) {
        relax();
        if (i % 64 == 0 && Clock::now() - begin >= spin) break;  // a clock read: some 20 ns
      }
    }
    while (!ready(s)) {
      state_.wait(s, std::memory_order_acquire);
      s = state_.load(std::memory_order_acquire);
    }
    last = Clock::now() - begin;
    return s;
  }

  /// Tells the core that this is a spin (an SMT sibling gets the pipeline, less power).
  static void relax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    asm volatile("yield");
#endif
  }

  const rumble::CosimHost& host_;
  std::uint32_t participant_;
  std::int64_t longest_spin_;  // ns
  std::atomic<std::uint32_t> state_{kIdle};
  std::atomic<std::int64_t> spin_ns_{0};  // ns, the spin before sleeping (0 before any request)
  Clock::duration done_wait_{}, request_wait_{};  // the last waits of wait() and of the worker
  // The request and its outcome, handed over through state_ (release, then acquire).
  double t_ = 0.0, h_ = 0.0;  // s, the step asked for
  bool save_ = false;
  std::uint32_t slot_ = 0;
  rumble_status status_ = RUMBLE_OK;
  std::exception_ptr error_;
  std::thread thread_;  // last: it starts after every member it uses exists
};

}  // namespace rumble_jacobi
