// The binary layout of rumble/abi.h is frozen by a committed table (abi_layout.txt): sizes,
// alignments and offsets of every struct, the type of every field (function signatures included)
// and every enum/constant value. An accidental change to the header fails here; an intended one
// (append-only: minor bump; anything else: major bump) updates the table in the same commit.
// This TU is compiled as C++17 (the SDK's language level); abi_layout_c.c measures the same list
// with the C compiler, and both must agree with the table.
#include <cxxabi.h>
#include <gtest/gtest.h>
#include <rumble/abi.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "abi_layout_entry.h"

namespace {

struct Item {
  std::string kind;  // struct, enum, field, const (see abi_layout_entry.h for a and b)
  std::string name;
  unsigned long long a = 0;
  unsigned long long b = 0;
  std::size_t align = 0;  // fields: alignof the field's type
  std::string type;       // fields: the C++ spelling of the field's type
};

std::string demangle(const std::type_info& t) {
  int status = 0;
  const std::unique_ptr<char, void (*)(void*)> text(
      abi::__cxa_demangle(t.name(), nullptr, nullptr, &status), std::free);
  return status == 0 && text ? std::string(text.get()) : std::string(t.name());
}

std::vector<Item> cxx_layout() {
#define RUMBLE_LAYOUT_STRUCT(T) {"struct", #T, sizeof(T), alignof(T), 0, ""},
#define RUMBLE_LAYOUT_ENUM(T) {"enum", #T, sizeof(T), alignof(T), 0, ""},
#define RUMBLE_LAYOUT_FIELD(T, f) \
  {"field",                       \
   #T "." #f,                     \
   offsetof(T, f),                \
   sizeof(T::f),                  \
   alignof(decltype(T::f)),       \
   demangle(typeid(decltype(T::f)))},
#define RUMBLE_LAYOUT_CONST(C) {"const", #C, static_cast<unsigned long long>(C), 0, 0, ""},
  return {
#include "abi_layout.def"
  };
#undef RUMBLE_LAYOUT_STRUCT
#undef RUMBLE_LAYOUT_ENUM
#undef RUMBLE_LAYOUT_FIELD
#undef RUMBLE_LAYOUT_CONST
}

std::string line_of(const Item& i) {
  std::string s = i.kind + " " + i.name + " " + std::to_string(i.a);
  if (i.kind != "const") s += " " + std::to_string(i.b);
  if (!i.type.empty()) s += " " + i.type;
  return s;
}

std::vector<std::string> read_table(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  }
  return lines;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const std::string kTablePath = RUMBLE_TEST_SOURCE_DIR "/tests/abi/abi_layout.txt";
const std::string kActualPath = ABI_TEST_BINARY_DIR "/abi_layout.actual.txt";

const char* const kTableHeader =
    "# rumble/abi.h binary layout on LP64 Linux (x86_64, aarch64), checked by\n"
    "# tests/abi/abi_layout_test.cpp against both the C and the C++ compiler. Lines:\n"
    "#   struct|enum <name> <sizeof> <alignof>\n"
    "#   field <struct>.<member> <offsetof> <sizeof> <type as C++ spells it>\n"
    "#   const <name> <value>\n"
    "# Never edit by hand: after an intended ABI change the failing test writes the new table to\n"
    "# <build>/tests/abi/abi_layout.actual.txt; review the diff and copy it here.\n";

// The table is measured on LP64 Linux (x86_64, aarch64); other data models differ legitimately.
bool is_lp64() {
  return sizeof(void*) == 8 && sizeof(long) == 8 && sizeof(int) == 4;
}

TEST(AbiLayout, MatchesCommittedTable) {
  if (!is_lp64()) GTEST_SKIP() << "abi_layout.txt holds the LP64 layout";
  const std::vector<std::string> expected = read_table(kTablePath);
  std::vector<std::string> actual;
  for (const Item& i : cxx_layout()) actual.push_back(line_of(i));
  if (actual != expected) {
    std::ofstream out(kActualPath);
    out << kTableHeader;
    for (const std::string& l : actual) out << l << "\n";
  }
  ASSERT_FALSE(expected.empty()) << "cannot read " << kTablePath;
  for (std::size_t k = 0; k < std::max(actual.size(), expected.size()); ++k) {
    const std::string a = k < actual.size() ? actual[k] : "(nothing)";
    const std::string e = k < expected.size() ? expected[k] : "(nothing)";
    ASSERT_EQ(a, e) << "rumble/abi.h layout changed at entry " << k << ". If intended (append "
                    << "only: bump RUMBLE_ABI_MINOR; otherwise RUMBLE_ABI_MAJOR), add a revision "
                    << "line to abi.h and copy " << kActualPath << " over " << kTablePath;
  }
}

// Growth is append-only in fact: every constant and every field of ABI 1.0 (the table frozen at
// its release) is still there with the same value, offset, size and type, and no struct shrank.
// Only RUMBLE_ABI_MINOR may differ.
TEST(AbiLayout, EveryAbi10FieldIsWhereItWas) {
  if (!is_lp64()) GTEST_SKIP() << "the tables hold the LP64 layout";
  const std::vector<std::string> v1_0 =
      read_table(RUMBLE_TEST_SOURCE_DIR "/tests/abi/abi_layout_1_0.txt");
  ASSERT_GT(v1_0.size(), 50u);
  std::set<std::string> now;
  std::map<std::string, unsigned long long> size_now;
  for (const Item& i : cxx_layout()) {
    now.insert(line_of(i));
    if (i.kind == "struct") size_now[i.name] = i.a;
  }
  for (const std::string& line : v1_0) {
    std::istringstream words(line);
    std::string kind, name;
    unsigned long long size = 0;
    words >> kind >> name >> size;
    if (name == "RUMBLE_ABI_MINOR") continue;
    if (kind == "struct") {
      EXPECT_GE(size_now[name], size) << name << " shrank";
    } else {
      EXPECT_EQ(now.count(line), 1u) << "ABI 1.0 entry changed or removed: " << line;
    }
  }
}

TEST(AbiLayout, CAndCxxCompilersAgree) {
  unsigned long long n = 0;
  const abi_layout_entry* c = abi_layout_from_c(&n);
  const std::vector<Item> cxx = cxx_layout();
  ASSERT_EQ(n, cxx.size());
  for (std::size_t k = 0; k < cxx.size(); ++k) {
    SCOPED_TRACE(cxx[k].name);
    EXPECT_EQ(c[k].kind, cxx[k].kind);
    EXPECT_EQ(c[k].name, cxx[k].name);
    EXPECT_EQ(c[k].a, cxx[k].a);
    EXPECT_EQ(c[k].b, cxx[k].b);
  }
}

// The fields listed for a struct, in order, must cover it exactly (only alignment padding in
// between and at the end): a field missing from abi_layout.def cannot hide in the table.
TEST(AbiLayout, ListedFieldsTileEveryStruct) {
  const std::vector<Item> items = cxx_layout();
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (items[k].kind != "struct") continue;
    const Item& s = items[k];
    SCOPED_TRACE(s.name);
    unsigned long long end = 0;
    std::size_t n_fields = 0;
    for (std::size_t j = k + 1; j < items.size() && items[j].kind == "field"; ++j, ++n_fields) {
      const Item& f = items[j];
      ASSERT_EQ(f.name.rfind(s.name + ".", 0), 0u) << f.name << " listed under " << s.name;
      const unsigned long long expected_offset = (end + f.align - 1) / f.align * f.align;
      EXPECT_EQ(f.a, expected_offset) << f.name << ": a field is missing before it in the list";
      end = f.a + f.b;
    }
    EXPECT_GT(n_fields, 0u);
    EXPECT_EQ(s.a, (end + s.b - 1) / s.b * s.b) << "a field is missing at the end of the list";
  }
}

// Every struct, enum, enumerator and numeric #define of abi.h is in abi_layout.def.
TEST(AbiLayout, ListCoversTheWholeHeader) {
  const std::string header = read_file(RUMBLE_TEST_SOURCE_DIR "/sdk/include/rumble/abi.h");
  ASSERT_FALSE(header.empty());
  std::set<std::string> listed;
  for (const Item& i : cxx_layout()) listed.insert(i.kind + " " + i.name);

  const std::vector<std::pair<std::regex, std::string>> patterns = {
      {std::regex(R"(typedef struct (rumble_\w+) \{)"), "struct"},
      {std::regex(R"(typedef enum (rumble_\w+) \{)"), "enum"},
      {std::regex(R"(\n\s*(RUMBLE_[A-Z0-9_]+) = )"), "const"},
      {std::regex(R"(#define (RUMBLE_[A-Z0-9_]+) [0-9]+u?\b)"), "const"}};
  std::size_t found = 0;
  for (const auto& [re, kind] : patterns) {
    for (auto it = std::sregex_iterator(header.begin(), header.end(), re);
         it != std::sregex_iterator(); ++it, ++found) {
      EXPECT_EQ(listed.count(kind + " " + (*it)[1].str()), 1u)
          << kind << " " << (*it)[1] << " is in abi.h but not in tests/abi/abi_layout.def";
    }
  }
  EXPECT_GT(found, 30u) << "the patterns no longer match abi.h's style";
}

// Versioning rule: every table/descriptor the other side may see in an older or newer size
// begins with its size in bytes, so that appended members can be detected.
TEST(AbiLayout, VersionedStructsBeginWithTheirSize) {
  const std::set<std::string> versioned = {"rumble_host",
                                           "rumble_vehicle_api",
                                           "rumble_soil_api",
                                           "rumble_coupler_api",
                                           "rumble_cosim_host",
                                           "rumble_factory",
                                           "rumble_plugin_descriptor",
                                           "rumble_lifecycle_api",
                                           "rumble_capabilities",
                                           "rumble_step_report"};
  const std::vector<Item> items = cxx_layout();
  std::size_t seen = 0;
  for (std::size_t k = 0; k + 1 < items.size(); ++k) {
    if (items[k].kind != "struct" || versioned.count(items[k].name) == 0) continue;
    ++seen;
    EXPECT_EQ(items[k + 1].name, items[k].name + ".struct_size");
    EXPECT_EQ(items[k + 1].a, 0u);
    EXPECT_EQ(items[k + 1].b, 4u);
  }
  EXPECT_EQ(seen, versioned.size());
}

TEST(AbiLayout, EntryPointNameIsFixedForever) {
  EXPECT_STREQ(RUMBLE_PLUGIN_ENTRY_SYMBOL, "rumble_plugin_entry");
}

}  // namespace
