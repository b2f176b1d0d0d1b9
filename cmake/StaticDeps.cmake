# Start-up (issue 22 item 1): the dynamic loader's work grows with the number
# of shared objects a tool maps. Debian's Ceres is a static archive that
# names its dependencies as shared libraries (glog, gflags, SuiteSparse,
# CXSparse, LAPACK/BLAS/ATLAS and through them gfortran, quadmath, gomp):
# 20 shared objects mapped at every start although a fit uses only Ceres's
# dense solvers. With DRIVEID_STATIC_DEPS the tools link the static archives
# Debian ships for these and for yaml-cpp and libcrypto instead; the linker
# takes only the objects that are referenced. What stays shared: libc, libm,
# libstdc++, libgcc_s, fmt (no archive in Debian), libunwind (its archive is
# not position-independent) with liblzma, and METIS (no archive).
#
# Every archive must be there, else the shared libraries are kept (a note,
# no failure): the tools behave the same either way.

option(DRIVEID_STATIC_DEPS "Link Ceres's dependencies, yaml-cpp and libcrypto statically (faster start)" ON)

function(driveid_static_deps)
  set(DRIVEID_YAML_LIB yaml-cpp PARENT_SCOPE)
  if(NOT DRIVEID_STATIC_DEPS OR DRIVEID_SANITIZE OR DRIVEID_FUZZ)
    return()
  endif()
  set(archives)
  foreach(name glog gflags spqr cholmod amd camd ccolamd colamd suitesparseconfig cxsparse lapack f77blas
               atlas blas yaml-cpp crypto)
    find_library(DRIVEID_STATIC_${name} NAMES lib${name}.a)
    if(NOT DRIVEID_STATIC_${name})
      message(STATUS "Static dependencies: lib${name}.a not found; linking the shared libraries")
      return()
    endif()
    list(APPEND archives ${DRIVEID_STATIC_${name}})
  endforeach()
  # The compiler's own runtime archives (libgfortran.a from gcc's libgfortran
  # development package, which Debian's gfortran pulls in).
  foreach(name gfortran quadmath gomp)
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=lib${name}.a OUTPUT_VARIABLE path
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(NOT IS_ABSOLUTE "${path}" OR NOT EXISTS "${path}")
      message(STATUS "Static dependencies: lib${name}.a not found; linking the shared libraries")
      return()
    endif()
  endforeach()
  find_library(DRIVEID_SHARED_unwind NAMES unwind)
  find_library(DRIVEID_SHARED_metis NAMES metis libmetis.so.5)
  if(NOT DRIVEID_SHARED_unwind OR NOT DRIVEID_SHARED_metis)
    message(STATUS "Static dependencies: libunwind or libmetis not found; linking the shared libraries")
    return()
  endif()
  # One group: the archives refer to each other in cycles (cholmod <-> lapack).
  set(deps "-Wl,--start-group" ${archives} "-Wl,-Bstatic" -lgfortran -lquadmath -lgomp "-Wl,-Bdynamic"
           "-Wl,--end-group" ${DRIVEID_SHARED_unwind} ${DRIVEID_SHARED_metis} Threads::Threads ${CMAKE_DL_LIBS}
           Eigen3::Eigen)
  set_property(TARGET Ceres::ceres PROPERTY INTERFACE_LINK_LIBRARIES "${deps}")
  # yaml-cpp and libcrypto: the same archives as in the group above.
  add_library(driveid_yaml_static INTERFACE IMPORTED GLOBAL)
  set_property(TARGET driveid_yaml_static PROPERTY INTERFACE_LINK_LIBRARIES ${DRIVEID_STATIC_yaml-cpp})
  get_target_property(yaml_includes yaml-cpp INTERFACE_INCLUDE_DIRECTORIES)
  if(yaml_includes)
    set_property(TARGET driveid_yaml_static PROPERTY INTERFACE_INCLUDE_DIRECTORIES ${yaml_includes})
  endif()
  set(DRIVEID_YAML_LIB driveid_yaml_static PARENT_SCOPE)
  set_property(TARGET OpenSSL::Crypto PROPERTY IMPORTED_LOCATION ${DRIVEID_STATIC_crypto})
  set_property(TARGET OpenSSL::Crypto APPEND PROPERTY INTERFACE_LINK_LIBRARIES Threads::Threads ${CMAKE_DL_LIBS})
  message(STATUS "Static dependencies: Ceres's, yaml-cpp's and libcrypto's archives (scripts/benchmark: start-up)")
endfunction()
