// Numbers in messages and text files, in printf's %g style.
#pragma once

#include <cstdio>
#include <string>

namespace rumble {

/// `value` with `significant_digits` (at most 17) digits as printf's %g writes it, which is also
/// what `std::ostream << value` writes at that precision: "0.5", "2.1e+11", "1e-09", "nan".
/// 6 (the default) is the stream's default precision, for messages; the engine's CSVs use 9.
inline std::string number_text(double value, int significant_digits = 6) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", significant_digits, value);
  return buf;
}

}  // namespace rumble
