// The plugin tests mesh every time (they are about the soil, and must not write to the user's
// cache): RUMBLE_MESH_CACHE=off before main().
#include <cstdlib>

namespace {
const int kNoMeshCache = ::setenv("RUMBLE_MESH_CACHE", "off", 1);
}  // namespace
