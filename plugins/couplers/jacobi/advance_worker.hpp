// A persistent thread that advances one participant when asked, so that a parallel scheme starts
// no thread per macro step (starting one costs tens of microseconds and allocates its stack:
// comparable to a reduced soil's whole step). One request at a time: start(), then wait().
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <rumble/plugin.hpp>
#include <thread>

namespace rumble_jacobi {

class AdvanceWorker {
 public:
  AdvanceWorker(const rumble::CosimHost& host, std::uint32_t participant)
      : host_(host), participant_(participant), thread_([this] { loop(); }) {}
  AdvanceWorker(const AdvanceWorker&) = delete;
  AdvanceWorker& operator=(const AdvanceWorker&) = delete;
  ~AdvanceWorker() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      state_ = State::kStopping;
    }
    changed_.notify_all();
    thread_.join();
  }

  /// The participant starts advancing over [t, t + h] on the worker thread.
  void start(double t, double h) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      t_ = t;
      h_ = h;
      error_ = nullptr;
      state_ = State::kRequested;
    }
    changed_.notify_all();
  }

  /// Waits for the step started last; returns its status or rethrows what it threw.
  rumble_status wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return state_ == State::kDone; });
    state_ = State::kIdle;
    if (error_) std::rethrow_exception(error_);
    return status_;
  }

 private:
  enum class State { kIdle, kRequested, kDone, kStopping };

  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock,
                    [this] { return state_ == State::kRequested || state_ == State::kStopping; });
      if (state_ == State::kStopping) return;
      lock.unlock();
      rumble_status status = RUMBLE_OK;
      std::exception_ptr error;
      try {
        status = host_.advance(participant_, t_, h_);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      status_ = status;
      error_ = error;
      state_ = State::kDone;
      changed_.notify_all();
    }
  }

  const rumble::CosimHost& host_;
  std::uint32_t participant_;
  std::mutex mutex_;
  std::condition_variable changed_;
  State state_ = State::kIdle;
  double t_ = 0.0, h_ = 0.0;  // s, the step asked for
  rumble_status status_ = RUMBLE_OK;
  std::exception_ptr error_;
  std::thread thread_;  // last: it starts after every member it uses exists
};

}  // namespace rumble_jacobi
