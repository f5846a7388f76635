// The dynamic symbols a shared library defines, read with readelf (binutils), for checking that
// a plugin exports only its entry point. Shared with tests/install (the template plugin).
#pragma once

#include <string>
#include <vector>

namespace rumble::test {

struct DynamicSymbol {
  std::string name;  // as readelf prints it (mangled, version suffix removed)
  std::string type;  // FUNC, OBJECT, ...
  std::string bind;  // GLOBAL, WEAK, UNIQUE
};

/// Symbols the library defines in its .dynsym (undefined references excluded). Throws
/// std::runtime_error when readelf cannot be run or fails on the file.
std::vector<DynamicSymbol> defined_dynamic_symbols(const std::string& readelf,
                                                   const std::string& library);

/// "name (BIND TYPE)" for each, one per line: readable failure messages.
std::string describe(const std::vector<DynamicSymbol>& symbols);

}  // namespace rumble::test
