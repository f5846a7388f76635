/* One measured item of the ABI layout, shared by the C and the C++ side of the layout test.
 * kind "struct"/"enum": a = sizeof, b = alignof; "field": a = offsetof, b = sizeof;
 * "const": a = value, b unused. */
#ifndef RUMBLE_TESTS_ABI_LAYOUT_ENTRY_H
#define RUMBLE_TESTS_ABI_LAYOUT_ENTRY_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct abi_layout_entry {
  const char* kind;
  const char* name;
  unsigned long long a;
  unsigned long long b;
} abi_layout_entry;

/** The layout as the C compiler sees it (abi_layout_c.c); *n receives the number of entries. */
const abi_layout_entry* abi_layout_from_c(unsigned long long* n);

#ifdef __cplusplus
}
#endif

#endif
