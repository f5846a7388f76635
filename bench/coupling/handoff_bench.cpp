// The handoff of jacobi's worker thread (plugins/couplers/jacobi/advance_worker.hpp) alone: per
// macro step the "soil" advances on the worker for W_soil us of work while the calling thread
// does W_track us of its own, then S us of serial work (the step report, the recording). Each
// step's wall time beyond the ideal, max(W_track, W_soil) + S, is what handing the step over and
// back costs. Three workers: a mutex and a condition variable (the worker before issue #32), the
// atomic worker without its spin, and the atomic worker as jacobi runs it. Work is a CPU loop
// calibrated at start, so run it on a quiet machine and state the load (bench/README.md).
//
// usage: handoff_bench [W_TRACK W_SOIL S [STEPS]]   (default: a table of cases)
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <rumble/plugin.hpp>
#include <thread>

#include "advance_worker.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double g_rounds_per_us = 0.0;  // of work(), calibrated
volatile double g_sink = 0.0;

void work_rounds(long n) {
  double x = 1.0;
  for (long i = 0; i < n; ++i) x = x * 1.0000001 + 1e-9;
  g_sink = x;
}
void work(double us) {
  work_rounds(static_cast<long>(us * g_rounds_per_us));
}
void calibrate() {
  constexpr long kRounds = 20'000'000;
  double best = 1e30;
  for (int k = 0; k < 5; ++k) {  // the fastest of five: the least disturbed
    const auto start = Clock::now();
    work_rounds(kRounds);
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  g_rounds_per_us = kRounds / (best * 1e6);
}

double g_soil_us = 0.0;  // the worker's work per step

/// The worker before issue #32: a mutex and a condition variable.
class MutexWorker {
 public:
  MutexWorker() : thread_([this] { loop(); }) {}
  MutexWorker(const MutexWorker&) = delete;
  MutexWorker& operator=(const MutexWorker&) = delete;
  ~MutexWorker() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      state_ = 3;
    }
    changed_.notify_all();
    thread_.join();
  }
  void start() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      state_ = 1;
    }
    changed_.notify_all();
  }
  void wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return state_ == 2; });
    state_ = 0;
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock, [this] { return state_ == 1 || state_ == 3; });
      if (state_ == 3) return;
      lock.unlock();
      work(g_soil_us);
      lock.lock();
      state_ = 2;
      changed_.notify_all();
    }
  }
  std::mutex mutex_;
  std::condition_variable changed_;
  int state_ = 0;
  std::thread thread_;
};

/// Microseconds per step beyond the ideal.
template <class Start, class Wait>
double over_ideal(double track_us, double serial_us, int steps, Start start, Wait wait) {
  const auto begin = Clock::now();
  for (int k = 0; k < steps; ++k) {
    start();
    work(track_us);
    wait();
    work(serial_us);
  }
  const double per_step =
      std::chrono::duration<double, std::micro>(Clock::now() - begin).count() / steps;
  return per_step - (std::max(track_us, g_soil_us) + serial_us);
}

void measure(double track_us, double soil_us, double serial_us, int steps) {
  g_soil_us = soil_us;
  rumble_cosim_host table{};
  table.struct_size = sizeof table;
  table.advance = [](void*, uint32_t, double, double) {
    work(g_soil_us);
    return RUMBLE_OK;
  };
  const rumble::CosimHost host(&table);
  MutexWorker mutex;
  const double m = over_ideal(
      track_us, serial_us, steps, [&] { mutex.start(); }, [&] { mutex.wait(); });
  rumble_jacobi::AdvanceWorker sleeping(host, 1, 0);
  const double a = over_ideal(
      track_us, serial_us, steps, [&] { sleeping.start(0.0, 1e-3); }, [&] { sleeping.wait(); });
  rumble_jacobi::AdvanceWorker spinning(host, 1);
  const double s = over_ideal(
      track_us, serial_us, steps, [&] { spinning.start(0.0, 1e-3); }, [&] { spinning.wait(); });
  std::printf("%8.0f %8.0f %8.0f %12.1f %12.1f %12.1f\n", track_us, soil_us, serial_us, m, a, s);
}

}  // namespace

int main(int argc, char** argv) {
  calibrate();
  std::printf(
      "us per step beyond max(track, soil) + serial: mutex + condition variable, atomic "
      "without spin, atomic with jacobi's spin\n");
  std::printf("%8s %8s %8s %12s %12s %12s\n", "track", "soil", "serial", "mutex+cv", "atomic",
              "atomic+spin");
  if (argc >= 4) {
    measure(std::atof(argv[1]), std::atof(argv[2]), std::atof(argv[3]),
            argc > 4 ? std::atoi(argv[4]) : 2000);
    return 0;
  }
  const double cases[][3] = {
      {30, 30, 5}, {100, 100, 5}, {300, 200, 10}, {1000, 1000, 20}, {2800, 2800, 110}};
  for (const auto& c : cases) measure(c[0], c[1], c[2], c[0] < 500 ? 5000 : 1000);
  return 0;
}
