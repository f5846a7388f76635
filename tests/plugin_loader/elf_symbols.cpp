#include "elf_symbols.hpp"

#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace rumble::test {

std::vector<DynamicSymbol> defined_dynamic_symbols(const std::string& readelf,
                                                   const std::string& library) {
  const std::string command = "'" + readelf + "' --dyn-syms --wide '" + library + "' 2>&1";
  const std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot run: " + command);
  std::string text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0;) {
    text.append(buffer, n);
  }
  // Lines: "Num: Value Size Type Bind Vis Ndx Name"; Ndx "UND" marks an undefined reference.
  std::vector<DynamicSymbol> symbols;
  std::istringstream lines(text);
  bool table = false;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string num, value, size, type, bind, vis, ndx, name;
    if (!(fields >> num >> value >> size >> type >> bind >> vis >> ndx)) continue;
    if (num == "Num:") {
      table = true;
      continue;
    }
    if (!table || ndx == "UND") continue;
    fields >> name;
    if (name.empty()) continue;
    symbols.push_back({name.substr(0, name.find('@')), type, bind});
  }
  if (!table) throw std::runtime_error(command + " printed no symbol table:\n" + text);
  return symbols;
}

std::string describe(const std::vector<DynamicSymbol>& symbols) {
  std::string s;
  for (const DynamicSymbol& d : symbols) s += "  " + d.name + " (" + d.bind + " " + d.type + ")\n";
  return s;
}

}  // namespace rumble::test
