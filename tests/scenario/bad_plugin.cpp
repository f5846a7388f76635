// A plugin with bugs that validation must name: a soil type without a params schema and one
// whose schema is not JSON. Written against the raw C ABI because the C++ layer cannot express
// a missing schema.
#include <rumble/abi.h>

#include "stub_soil_api.h"

namespace {

rumble_status create(const char*, const rumble_host*, rumble_instance** out, const char** error) {
  *out = nullptr;
  *error = "test plugin: not creatable";
  return RUMBLE_ERROR;
}

const rumble_soil_api kApi = {.struct_size = sizeof(rumble_soil_api),
                              .common = RUMBLE_STUB_COMMON_API,
                              .accept_layout = rumble_stub_accept_layout,
                              .initialize = rumble_stub_initialize,
                              .advance = rumble_stub_advance,
                              .motion = rumble_stub_motion,
                              .frequency_response = nullptr,
                              .set_receivers = nullptr,
                              .receiver_velocity = nullptr,
                              .lifecycle = nullptr,
                              .set_probes = nullptr,
                              .probe_samples = nullptr,
                              .write_fields = nullptr,
                              .wave_speeds = nullptr,
                              .linear_matrix = nullptr,
                              .probe_resolution = nullptr,
                              .size = nullptr,
                              .statics_done = nullptr};

const rumble_factory kFactories[] = {
    {sizeof(rumble_factory), RUMBLE_KIND_SOIL, "no_schema_soil", "test: declares no schema",
     nullptr, &create, &kApi, nullptr},
    {sizeof(rumble_factory), RUMBLE_KIND_SOIL, "bad_schema_soil", "test: schema is not JSON",
     "{\"type\": \"object\", ", &create, &kApi, nullptr},
};

const rumble_plugin_descriptor kDescriptor = {sizeof(rumble_plugin_descriptor),
                                              RUMBLE_ABI_MAJOR,
                                              RUMBLE_ABI_MINOR,
                                              "bad_plugin",
                                              "0.0.1",
                                              "test",
                                              2,
                                              kFactories};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rumble_plugin_descriptor*
rumble_plugin_entry() {
  return &kDescriptor;
}
