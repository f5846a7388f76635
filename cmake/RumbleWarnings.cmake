# Warnings for every target of this project (not imposed on third-party SDK users).
add_compile_options(
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough
  $<$<BOOL:${RUMBLE_WERROR}>:-Werror>)
# C sources (the ABI compile test) do not know the C++-only flags.
set(CMAKE_C_FLAGS "${CMAKE_C_FLAGS} -Wall -Wextra -Wpedantic")
# GCC 12 reports false -Warray-bounds positives inside std::map when nlohmann::json objects are
# built from initializer lists at -O2 (GCC bug 107138 family), and false -Wrestrict positives
# in std::string's memcpy at -O3 (GCC bug 105329); later GCCs do not.
# -Wnull-dereference stays a warning there, not an error: GCC 12 reports "potential null pointer
# dereference" inside nlohmann::json and Eigen depending on what it inlines, and a unity batch
# (CMAKE_UNITY_BUILD) changes that whenever a source file is added (measured: adding one engine
# file made study/expansion.cpp fail in basic_json::is_string). The ASan/UBSan run catches real
# null dereferences.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-Wno-array-bounds> $<$<COMPILE_LANGUAGE:CXX>:-Wno-restrict>
                      $<$<COMPILE_LANGUAGE:CXX>:-Wno-error=null-dereference>)
endif()
# With -fsanitize=address at -O1, GCC 12 reports -Wmaybe-uninitialized inside libstdc++
# (std::function in <regex>, used by the JSON Schema validator); the flow analysis is
# confused by the sanitizer's instrumentation (GCC documents this). The normal build keeps it.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_FLAGS MATCHES "-fsanitize=")
  add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-Wno-maybe-uninitialized>)
endif()
