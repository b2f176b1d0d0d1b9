# Precompiled third-party headers (CMake's target_precompile_headers): each
# heavy header (Eigen, fmt, Catch2, CLI11 and the standard library around
# them) is parsed once per target instead of once per file. Only headers of
# other projects go in, so a file still has to include what it uses of this
# project's layers (the layering test and the layers' include roots see
# every include as before).
#
# driveid_precompile(TARGET HEADER...)         a target's own precompiled header
# driveid_precompile_reuse(TARGET FROM)        the precompiled header of FROM (same flags)
# The sanitizer preset (CMakePresets.json) turns them off: clang writes the
# clone's absolute paths into a precompiled header, and ccache hashes the
# header's contents, so no compilation that used one could hit the cache of
# another clone (a clean clone's sanitizer build compiled all 500 objects,
# 13 of CI's 38 minutes); without it each object is found in the cache
# another clone filled (CCACHE_BASEDIR). GCC's Release build keeps them (its
# .gch does not defeat the cache). Without the standard headers below, a
# file that forgot an include fails there first.
option(DRIVEID_PCH "Precompile the third-party headers" ON)

set(DRIVEID_PCH_STD <algorithm> <cmath> <functional> <map> <memory> <optional> <string> <vector>)

function(driveid_precompile target)
  if(DRIVEID_PCH)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

function(driveid_precompile_reuse target from)
  if(DRIVEID_PCH)
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endfunction()

# ccache (CMakeLists.txt) caches a compilation that uses a precompiled
# header only if clang writes no time stamp into the header.
if(DRIVEID_PCH AND CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache" AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  add_compile_options("$<$<COMPILE_LANGUAGE:CXX>:SHELL:-Xclang -fno-pch-timestamp>")
endif()
