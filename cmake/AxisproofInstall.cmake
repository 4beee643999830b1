# `cmake --install <build> --prefix P`: the harness as a CMake package, so that a firmware team
# can keep its profile in its own repository (docs/profiles.md "Your own firmware").
#
#   ap_install(TARGETS <target>... [HEADERS <folder>...] [FILES <header>...] [SUBDIR <dir>])
#       In a shared folder's CMakeLists.txt: installs the libraries into the export set
#       axisproofTargets (imported as axisproof::<target>), the headers under
#       include/axisproof[/SUBDIR] (HEADERS: a folder's include/ tree, copied as it is; FILES:
#       single headers), and makes the targets' usage requirements name that include folder
#       once installed. Each target also gets the alias axisproof::<target> here, so a profile's
#       CMake lists may use either name in this tree and outside it.
#   ap_install_package()
#       At the end of the top CMakeLists.txt: the target ap_package (builds what is installed)
#       and the package itself (<libdir>/cmake/axisproof:
#       axisproofConfig.cmake, its version, the exported targets, the CMake modules the
#       profiles' lists call, what this build was configured with) and the kit files
#       (share/axisproof: the replay driver, the CLI's process plumbing, the heap check, the DDS
#       loopback configuration; include/axisproof/testing: the profiles' end-to-end test helpers).
#
# Nothing is installed from the cross build (AP_MCU_ONLY): its archives are Cortex-M4 code.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(AP_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/axisproof)
set(AP_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/axisproof)
set(AP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/axisproof)

function(ap_install)
  cmake_parse_arguments(A "" "SUBDIR" "TARGETS;HEADERS;FILES" ${ARGN})
  set(_dest ${AP_INSTALL_INCLUDEDIR})
  if(A_SUBDIR)
    set(_dest ${_dest}/${A_SUBDIR})
  endif()
  foreach(_t IN LISTS A_TARGETS)
    add_library(axisproof::${_t} ALIAS ${_t})
    if(AP_MCU_ONLY)
      continue()
    endif()
    # A folder's include/ (or the build's generated headers) is where its headers are in this
    # tree; installed, they are under include/axisproof. Other paths (a system library's) and
    # paths a generator expression already places are left as they are.
    set(_moved OFF)
    foreach(_prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
      get_target_property(_dirs ${_t} ${_prop})
      if(NOT _dirs)
        continue()
      endif()
      set(_new "")
      foreach(_d IN LISTS _dirs)
        cmake_path(IS_PREFIX PROJECT_SOURCE_DIR "${_d}" NORMALIZE _in_src)
        cmake_path(IS_PREFIX PROJECT_BINARY_DIR "${_d}" NORMALIZE _in_bin)
        if(NOT _d MATCHES "^\\$<" AND (_in_src OR _in_bin))
          list(APPEND _new "$<BUILD_INTERFACE:${_d}>")
          set(_moved ON)
        else()
          list(APPEND _new "${_d}")
        endif()
      endforeach()
      set_target_properties(${_t} PROPERTIES ${_prop} "${_new}")
    endforeach()
    if(_moved)
      set_property(TARGET ${_t} APPEND PROPERTY INTERFACE_INCLUDE_DIRECTORIES "$<INSTALL_INTERFACE:${_dest}>")
    endif()
    install(TARGETS ${_t} EXPORT axisproofTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
    set_property(GLOBAL APPEND PROPERTY AP_EXPORTED_TARGETS ${_t})
  endforeach()
  if(AP_MCU_ONLY)
    return()
  endif()
  foreach(_h IN LISTS A_HEADERS)
    install(DIRECTORY ${_h}/ DESTINATION ${_dest})
  endforeach()
  if(A_FILES)
    install(FILES ${A_FILES} DESTINATION ${_dest})
  endif()
endfunction()

# What an outside project must match or take over from this build: its flags (the libraries
# are instrumented with them) and how the Z3 library was found.
function(_ap_write_build_info out)
  set(_text "# What the installed harness was built with (written by its CMake configure).\n")
  foreach(_v AP_SANITIZE AP_COVERAGE AP_FUZZ AP_FUZZ_BINARIES AP_WERROR)
    if(${_v})
      set(_b ON)
    else()
      set(_b OFF)
    endif()
    string(APPEND _text "set(AXISPROOF_BUILT_${_v} ${_b})\n")
  endforeach()
  # models/smt wraps Debian's Z3 (no CMake package) in ap_z3, installed with it; a Z3 with
  # a CMake package is found again by the config.
  if(TARGET ap_z3)
    set(_z3 ap_z3)
  else()
    set(_z3 z3::libz3)
  endif()
  string(APPEND _text "set(AXISPROOF_BUILT_AP_LAYER_OPTIONS \"${AP_LAYER_OPTIONS}\")\n"
                      "set(AXISPROOF_BUILT_AP_FUZZ_ENGINE \"${AP_FUZZ_ENGINE}\")\n"
                      "set(AXISPROOF_BUILT_CXX_COMPILER_ID \"${CMAKE_CXX_COMPILER_ID}\")\n"
                      "set(AXISPROOF_BUILT_CXX_COMPILER_VERSION \"${CMAKE_CXX_COMPILER_VERSION}\")\n"
                      "set(AXISPROOF_BUILT_BUILD_TYPE \"${CMAKE_BUILD_TYPE}\")\n"
                      "set(AXISPROOF_BUILT_Z3_TARGET \"${_z3}\")\n")
  file(WRITE ${out}.new "${_text}")
  file(COPY_FILE ${out}.new ${out} ONLY_IF_DIFFERENT)
  file(REMOVE ${out}.new)
endfunction()

function(ap_install_package)
  if(AP_MCU_ONLY)
    return()
  endif()
  # `cmake --build <build> --target ap_package`: only what `cmake --install` copies, for a
  # harness built to be installed rather than tested (docs/profiles.md "Your own firmware").
  get_property(_exported GLOBAL PROPERTY AP_EXPORTED_TARGETS)
  add_custom_target(ap_package)
  foreach(_t IN LISTS _exported)
    get_target_property(_type ${_t} TYPE)
    if(NOT _type STREQUAL "INTERFACE_LIBRARY")
      add_dependencies(ap_package ${_t})
    endif()
  endforeach()
  set(_gen ${CMAKE_BINARY_DIR}/package)
  _ap_write_build_info(${_gen}/axisproofBuildInfo.cmake)
  get_property(AP_EXPORTED_TARGETS GLOBAL PROPERTY AP_EXPORTED_TARGETS)
  file(RELATIVE_PATH AP_CONFIG_TO_PREFIX /prefix/${AP_INSTALL_CMAKEDIR} /prefix)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/axisproofConfig.cmake.in ${_gen}/axisproofConfig.cmake @ONLY)
  write_basic_package_version_file(${_gen}/axisproofConfigVersion.cmake
                                   VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
  install(EXPORT axisproofTargets NAMESPACE axisproof:: DESTINATION ${AP_INSTALL_CMAKEDIR})
  install(FILES ${_gen}/axisproofConfig.cmake ${_gen}/axisproofConfigVersion.cmake ${_gen}/axisproofBuildInfo.cmake
          DESTINATION ${AP_INSTALL_CMAKEDIR})
  # The modules a profile's CMake lists call (ap_declare_profile, ap_core_library, ap_add_test,
  # ...), the same files this tree includes.
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/AxisproofWarnings.cmake ${PROJECT_SOURCE_DIR}/cmake/AxisproofTargets.cmake
                ${PROJECT_SOURCE_DIR}/cmake/AxisproofSubdirs.cmake ${PROJECT_SOURCE_DIR}/cmake/AxisproofGlob.cmake
                ${PROJECT_SOURCE_DIR}/cmake/AxisproofProfiles.cmake ${PROJECT_SOURCE_DIR}/cmake/AxisproofProject.cmake
          DESTINATION ${AP_INSTALL_CMAKEDIR})
  install(PROGRAMS ${PROJECT_SOURCE_DIR}/ci/check-no-heap DESTINATION ${AP_INSTALL_DATADIR}/ci)
  # The profiles' end-to-end tests share these helpers (properties/sim; AP_SIM_TEST_SUPPORT_DIR).
  install(FILES ${PROJECT_SOURCE_DIR}/properties/sim/profile_sim_support.hpp DESTINATION ${AP_INSTALL_INCLUDEDIR}/testing)
endfunction()
