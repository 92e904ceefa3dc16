# Precompiled headers for the third-party headers that nearly every file includes and that cost more
# to parse than most of our files cost to compile: Eigen (~2 s a file), nlohmann/json (~3 s), CLI11
# (~8 s), GoogleTest. One precompiled header per kind of target — the layers, the command-line
# program, the tests — compiled once and reused by every target of that kind (REUSE_FROM; their
# compile flags agree). docs/RELIABILITY.md has the build times with and without.
#
# A compiler launcher (ccache) caches nothing that includes a precompiled header unless told to be
# sloppy about it, so with a launcher the default is off: ccache then does the saving.
if(DEFINED CMAKE_CXX_COMPILER_LAUNCHER AND NOT CMAKE_CXX_COMPILER_LAUNCHER STREQUAL "")
  set(myo_pch_default OFF)
else()
  set(myo_pch_default ON)
endif()
option(MYO_PRECOMPILED_HEADERS "Precompile Eigen, nlohmann/json, CLI11 and GoogleTest once per kind of target" ${myo_pch_default})

set(MYO_PCH_HEADERS_layer <Eigen/Dense> <Eigen/Sparse> <string> <vector> <memory> <map>)
set(MYO_PCH_HEADERS_app <CLI/CLI.hpp> <nlohmann/json.hpp> <fmt/core.h> <Eigen/Dense> <Eigen/Sparse> <filesystem> <string> <vector>)
set(MYO_PCH_HEADERS_test <gtest/gtest.h> <nlohmann/json.hpp> <Eigen/Dense> <Eigen/Sparse> <filesystem> <string> <vector>)

# myo_precompile(TARGET KIND): KIND is layer, app or test. The first target of a kind compiles the
# header; the others reuse it.
function(myo_precompile target kind)
  if(NOT MYO_PRECOMPILED_HEADERS)
    return()
  endif()
  get_property(provider GLOBAL PROPERTY MYO_PCH_PROVIDER_${kind})
  if(provider)
    target_precompile_headers(${target} REUSE_FROM ${provider})
  else()
    target_precompile_headers(${target} PRIVATE ${MYO_PCH_HEADERS_${kind}})
    set_property(GLOBAL PROPERTY MYO_PCH_PROVIDER_${kind} ${target})
  endif()
  # GCC 12 reports, through a precompiled header, libstdc++'s own memcpy inside std::string as
  # stringop-overflow / -overread / array-bounds (char_traits.h: a system header, whose diagnostics
  # are silent without the precompiled header). Builds without it (MYO_PRECOMPILED_HEADERS=OFF) keep
  # these warnings for our code. Every target of a kind must have the provider's include paths and
  # definitions (GCC refuses the header otherwise): test programs link at least myo_core.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-stringop-overflow -Wno-stringop-overread -Wno-array-bounds)
  endif()
endfunction()
