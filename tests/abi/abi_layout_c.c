/* rumble/abi.h compiled as C11 (-Wall -Wextra -Wpedantic -Wstrict-prototypes -Werror: see
 * CMakeLists.txt), measuring the layout a C plugin would get. The C++ test compares it with its
 * own measurement and with the committed table. */
#include <rumble/abi.h>
#include <stddef.h>

#include "abi_layout_entry.h"

#define RUMBLE_LAYOUT_STRUCT(T) {"struct", #T, sizeof(T), _Alignof(T)},
#define RUMBLE_LAYOUT_ENUM(T) {"enum", #T, sizeof(T), _Alignof(T)},
#define RUMBLE_LAYOUT_FIELD(T, f) {"field", #T "." #f, offsetof(T, f), sizeof(((T*)0)->f)},
#define RUMBLE_LAYOUT_CONST(C) {"const", #C, (C), 0},

static const abi_layout_entry kEntries[] = {
#include "abi_layout.def"
};

const abi_layout_entry* abi_layout_from_c(unsigned long long* n) {
  *n = sizeof kEntries / sizeof kEntries[0];
  return kEntries;
}
