// Owners of FFTW3 plans and their buffers, so that every transform in the post-processing is
// planned once per length (FFTW_ESTIMATE: no timing runs, the input is never touched while
// planning) and then executed as often as needed. FFTW's planner is not thread-safe: make these
// objects from one thread at a time (executing different plans concurrently is safe).
//
// Conventions are FFTW's (unnormalised): forward X_k = sum_n x_n exp(-2 pi i k n / N), backward
// x_n = sum_k X_k exp(+2 pi i k n / N), so a forward then backward transform multiplies by N.
#pragma once

#include <complex>
#include <cstddef>
#include <span>

struct fftw_plan_s;  // FFTW's opaque plan type (fftw_plan is a pointer to it)

namespace rumble::post {

/// Real-to-complex forward transform of length n: n real inputs, n/2 + 1 complex outputs.
class RealFft {
 public:
  explicit RealFft(std::size_t n);
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  std::size_t size() const { return n_; }
  std::span<double> input() { return {in_, n_}; }
  std::span<const std::complex<double>> output() const { return {out_, n_ / 2 + 1}; }
  void execute();

 private:
  std::size_t n_ = 0;
  double* in_ = nullptr;
  std::complex<double>* out_ = nullptr;
  fftw_plan_s* plan_ = nullptr;
};

/// Complex transform of length n in one direction (forward: sign -1, backward: sign +1),
/// out of place: input() is left as it was.
class ComplexFft {
 public:
  enum class Direction { kForward, kBackward };
  ComplexFft(std::size_t n, Direction direction);
  ~ComplexFft();
  ComplexFft(const ComplexFft&) = delete;
  ComplexFft& operator=(const ComplexFft&) = delete;

  std::size_t size() const { return n_; }
  std::span<std::complex<double>> input() { return {in_, n_}; }
  std::span<const std::complex<double>> output() const { return {out_, n_}; }
  void execute();

 private:
  std::size_t n_ = 0;
  std::complex<double>* in_ = nullptr;
  std::complex<double>* out_ = nullptr;
  fftw_plan_s* plan_ = nullptr;
};

/// The smallest length >= n whose only prime factors are 2, 3, 5 and 7, for which FFTW's
/// algorithms are fastest (a zero-padded transform may use any such length).
std::size_t fft_friendly_size(std::size_t n);

}  // namespace rumble::post
