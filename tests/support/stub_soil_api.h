/* Stub functions for soil function tables written by hand against abi.h in test fixtures (C or
 * C++): present, because the loader refuses a table without the functions the engine calls
 * unconditionally, and refusing every call. static inline: a fixture that leaves one out on
 * purpose gets no unused-function warning. */
#ifndef RUMBLE_TESTS_STUB_SOIL_API_H
#define RUMBLE_TESTS_STUB_SOIL_API_H

#include <rumble/abi.h>

static inline void rumble_stub_destroy(rumble_instance* self) {
  (void)self;
}
static inline const char* rumble_stub_last_message(const rumble_instance* self) {
  (void)self;
  return "";
}
static inline rumble_status rumble_stub_state_size(rumble_instance* self, uint64_t* n) {
  (void)self;
  *n = 0;
  return RUMBLE_OK;
}
static inline rumble_status rumble_stub_save(rumble_instance* self, double* b, uint64_t n) {
  (void)self, (void)b, (void)n;
  return RUMBLE_ERROR;
}
static inline rumble_status rumble_stub_restore(rumble_instance* self, const double* b,
                                                uint64_t n) {
  (void)self, (void)b, (void)n;
  return RUMBLE_ERROR;
}
static inline rumble_status rumble_stub_accept_layout(rumble_instance* self,
                                                      const rumble_footprint* f, uint64_t n) {
  (void)self, (void)f, (void)n;
  return RUMBLE_ERROR;
}
static inline rumble_status rumble_stub_initialize(rumble_instance* self, double t0,
                                                   const double* f, double* u, uint64_t n) {
  (void)self, (void)t0, (void)f, (void)u, (void)n;
  return RUMBLE_ERROR;
}
static inline rumble_status rumble_stub_advance(rumble_instance* self, double t, double H,
                                                const rumble_waveform* w) {
  (void)self, (void)t, (void)H, (void)w;
  return RUMBLE_ERROR;
}
static inline rumble_status rumble_stub_motion(rumble_instance* self, double* u, double* v,
                                               uint64_t n) {
  (void)self, (void)u, (void)v, (void)n;
  return RUMBLE_ERROR;
}

/* The common part of any kind's table. */
#define RUMBLE_STUB_COMMON_API                                                               \
  {                                                                                          \
    rumble_stub_destroy, rumble_stub_last_message, rumble_stub_state_size, rumble_stub_save, \
        rumble_stub_restore                                                                  \
  }

#endif /* RUMBLE_TESTS_STUB_SOIL_API_H */
