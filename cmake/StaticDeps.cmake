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
  set(DRIVEID_CRYPTO_LIB OpenSSL::Crypto PARENT_SCOPE)
  if(NOT DRIVEID_STATIC_DEPS OR DRIVEID_SANITIZE)
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
  # A shared object (the Python module, python/) cannot take these archives
  # (libgfortran.a, libgflags.a are not position-independent): a target
  # with the property DRIVEID_SHARED_DEPS links Debian's shared libraries,
  # chosen per linked target by a generator expression.
  set(shared_case "$<BOOL:$<TARGET_PROPERTY:DRIVEID_SHARED_DEPS>>")
  get_target_property(shared_deps Ceres::ceres INTERFACE_LINK_LIBRARIES)
  set(chosen)
  foreach(item IN LISTS deps)
    list(APPEND chosen "$<$<NOT:${shared_case}>:${item}>")
  endforeach()
  foreach(item IN LISTS shared_deps)
    list(APPEND chosen "$<${shared_case}:${item}>")
  endforeach()
  set_property(TARGET Ceres::ceres PROPERTY INTERFACE_LINK_LIBRARIES "${chosen}")
  # yaml-cpp and libcrypto: the same archives as in the group above.
  add_library(driveid_yaml_static INTERFACE IMPORTED GLOBAL)
  get_target_property(yaml_includes yaml-cpp INTERFACE_INCLUDE_DIRECTORIES)
  if(yaml_includes)
    set_property(TARGET driveid_yaml_static PROPERTY INTERFACE_INCLUDE_DIRECTORIES ${yaml_includes})
  endif()
  set_property(TARGET driveid_yaml_static PROPERTY INTERFACE_LINK_LIBRARIES
               "$<$<NOT:${shared_case}>:${DRIVEID_STATIC_yaml-cpp}>" "$<${shared_case}:yaml-cpp>")
  set(DRIVEID_YAML_LIB driveid_yaml_static PARENT_SCOPE)
  get_target_property(crypto_shared OpenSSL::Crypto IMPORTED_LOCATION)
  if(NOT crypto_shared)
    get_target_property(crypto_shared OpenSSL::Crypto IMPORTED_LOCATION_RELEASE)
  endif()
  add_library(driveid_crypto INTERFACE IMPORTED GLOBAL)
  get_target_property(crypto_includes OpenSSL::Crypto INTERFACE_INCLUDE_DIRECTORIES)
  if(crypto_includes)
    set_property(TARGET driveid_crypto PROPERTY INTERFACE_INCLUDE_DIRECTORIES ${crypto_includes})
  endif()
  set_property(TARGET driveid_crypto PROPERTY INTERFACE_LINK_LIBRARIES
               "$<$<NOT:${shared_case}>:${DRIVEID_STATIC_crypto};Threads::Threads;${CMAKE_DL_LIBS}>"
               "$<${shared_case}:${crypto_shared}>")
  set(DRIVEID_CRYPTO_LIB driveid_crypto PARENT_SCOPE)
  message(STATUS "Static dependencies: Ceres's, yaml-cpp's and libcrypto's archives (scripts/benchmark: start-up)")
endfunction()
