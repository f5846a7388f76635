#include "operator/blas_threads.hpp"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>

namespace rumble::fem {

namespace {

struct OpenBlas {
  void (*set)(int) = nullptr;
  int (*get)() = nullptr;
};

/// OpenBLAS's two calls, looked up once: in libopenblas.so.0 where it is loaded (behind
/// libblas.so.3, which the engine's LAPACKE loads with the executable), else in the process's
/// global scope (an OpenBLAS under another name). Both absent: another BLAS.
const OpenBlas& openblas() {
  static const OpenBlas found = [] {
    OpenBlas o;
    void* library = ::dlopen("libopenblas.so.0", RTLD_LAZY | RTLD_NOLOAD);
    void* scope = library != nullptr ? library : RTLD_DEFAULT;
    o.set = reinterpret_cast<void (*)(int)>(::dlsym(scope, "openblas_set_num_threads"));
    o.get = reinterpret_cast<int (*)()>(::dlsym(scope, "openblas_get_num_threads"));
    if (library != nullptr) ::dlclose(library);  // (NOLOAD's reference: its users keep it loaded)
    return o.set != nullptr && o.get != nullptr ? o : OpenBlas{};
  }();
  return found;
}

bool users_choice() {
  for (const char* name : kBlasThreadChoices)
    if (std::getenv(name) != nullptr) return true;
  return false;
}

// BLAS's thread count before keep_blas_on_one_thread; 0 while unchanged.
std::atomic<int> threads_before{0};

}  // namespace

int blas_threads() {
  const OpenBlas& o = openblas();
  return o.get != nullptr ? o.get() : 0;
}

int keep_blas_on_one_thread() {
  const OpenBlas& o = openblas();
  if (o.set == nullptr || users_choice()) return 0;
  int unchanged = 0;  // (the first call's count is the one to report)
  threads_before.compare_exchange_strong(unchanged, o.get());
  o.set(1);
  return threads_before.load();
}

}  // namespace rumble::fem
