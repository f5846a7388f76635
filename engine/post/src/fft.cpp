#include "post/fft.hpp"

#include <fftw3.h>

#include <limits>
#include <new>
#include <stdexcept>
#include <string>

namespace rumble::post {
namespace {

// FFTW takes int lengths; our records are far shorter, but say so rather than wrap around.
int checked_length(std::size_t n, const char* what) {
  if (n == 0 || n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::invalid_argument(std::string(what) + ": FFT length " + std::to_string(n) +
                                " is outside 1.." +
                                std::to_string(std::numeric_limits<int>::max()));
  return static_cast<int>(n);
}

template <class T>
T* allocate(std::size_t count) {
  void* p = fftw_malloc(sizeof(T) * count);  // SIMD-aligned, as FFTW's fast paths want
  if (p == nullptr) throw std::bad_alloc();
  return static_cast<T*>(p);
}

// std::complex<double> and fftw_complex (double[2]) have the same layout (C++ [complex.numbers]
// and the FFTW manual, "Complex numbers").
fftw_complex* as_fftw(std::complex<double>* p) {
  return reinterpret_cast<fftw_complex*>(p);
}

}  // namespace

RealFft::RealFft(std::size_t n) : n_(n) {
  const int len = checked_length(n, "RealFft");
  in_ = allocate<double>(n);
  out_ = allocate<std::complex<double>>(n / 2 + 1);
  plan_ = fftw_plan_dft_r2c_1d(len, in_, as_fftw(out_), FFTW_ESTIMATE);
  if (plan_ == nullptr) {
    fftw_free(in_);
    fftw_free(out_);
    throw std::runtime_error("FFTW could not plan a real transform of length " + std::to_string(n));
  }
}

RealFft::~RealFft() {
  fftw_destroy_plan(plan_);
  fftw_free(in_);
  fftw_free(out_);
}

void RealFft::execute() {
  fftw_execute(plan_);
}

ComplexFft::ComplexFft(std::size_t n, Direction direction) : n_(n) {
  const int len = checked_length(n, "ComplexFft");
  in_ = allocate<std::complex<double>>(n);
  out_ = allocate<std::complex<double>>(n);
  plan_ = fftw_plan_dft_1d(len, as_fftw(in_), as_fftw(out_),
                           direction == Direction::kForward ? FFTW_FORWARD : FFTW_BACKWARD,
                           FFTW_ESTIMATE);
  if (plan_ == nullptr) {
    fftw_free(in_);
    fftw_free(out_);
    throw std::runtime_error("FFTW could not plan a complex transform of length " +
                             std::to_string(n));
  }
}

ComplexFft::~ComplexFft() {
  fftw_destroy_plan(plan_);
  fftw_free(in_);
  fftw_free(out_);
}

void ComplexFft::execute() {
  fftw_execute(plan_);
}

std::size_t fft_friendly_size(std::size_t n) {
  if (n <= 1) return 1;
  for (std::size_t m = n;; ++m) {
    std::size_t r = m;
    for (std::size_t p : {2u, 3u, 5u, 7u})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

}  // namespace rumble::post
