# Helper functions that give every layer the same shape.
#
#   ap_core_library(<name> SOURCES ... [DEPS ...])
#       A static library of the firmware core: no exceptions, no RTTI, and a post-build
#       check that no object references the heap (operator new/delete, malloc, free, ...).
#       DEPS may only name other core libraries or the folder's AP_CORE_DEPS (the layer rule):
#       a profile's core/<profile>/CMakeLists.txt may set AP_CORE_DEPS to its protocol's
#       header-only layout library, which every core library of that folder then links.
#   ap_add_test(<name> LABEL <unit|property|proof|fuzz|e2e> SOURCES ... [LIBS ...])
#       A GoogleTest + RapidCheck executable whose tests ctest discovers with that label and
#       the label of the profile they belong to (AP_PROFILE, below).
#   ap_test_labels(<test>... LABEL <kind>)
#       The same two labels for tests made with add_test().
#   ap_add_fuzz_target(<name> SOURCES ... [LIBS ...])
#       In the fuzz preset: a libFuzzer binary fuzz_<name>. In every preset: a plain
#       replay driver replay_<name> and a ctest (label fuzz) that replays its corpus and
#       regressions. A target's data sit in its profile's fuzz folder (AP_PROFILE_DIR,
#       fuzz/<profile>): corpus/<name>, regressions/<name>, dict/<name or group>.dict.
#       Every target is listed in <build>/fuzz_targets.txt (name, group, fuzz binary or "-",
#       replay binary, profile, data folder; tab-separated),
#       which `axisproof fuzz`, ci/nightly-fuzz and .clusterfuzzlite/build.sh read.
#   <build>/core_libs.txt lists each core library and its archive (the Cortex-M4 size table
#   and symbol check read it).
#
# AP_PROFILE: the firmware profile (docs/profiles.md) the tests and fuzz targets of a folder
# belong to, set by the folder (or inherited from its parent): the profile's name (set by
# ap_add_profile_dirs for its <layer>/<profile> folders), or `harness` for the harness's own
# checks. The gate selects a profile's tests by this label (ctest -L '^P$').
# A test or fuzz target defined where it is unset is a configure error.
# AP_MCU_ONLY (the m4 preset): only the protocol, core and firmware layers are configured, their
# shared folders and AP_MCU_PROFILE's own;
# ap_add_test, ap_add_fuzz_target and ap_add_bench do nothing.
# AP_FUZZ_ENGINE (set by .clusterfuzzlite/build.sh from $LIB_FUZZING_ENGINE): link flags of an
# external fuzzing engine, used instead of -fsanitize=fuzzer.
# AP_FUZZ_BINARIES (the asan preset): also build the libFuzzer binaries fuzz_<name>, with every
# object compiled with -fsanitize=fuzzer-no-link, but without the fuzz preset's other switches
# (no AP_FUZZING_BUILD, Debug). One clang build then serves the tests, the gate's fuzz smoke
# and (with AP_COVERAGE) the coverage report; the fuzz preset stays the optimised one for
# long fuzzing runs (`axisproof fuzz`).

# The harness's files the functions below use: this tree's, or, in a project that found the
# installed harness (find_package(axisproof) sets AP_PACKAGE_DATA_DIR and these), the package's
# copies. AP_FUZZ_KIT_DIR: the fuzz kit (the replay driver); AP_CHECK_NO_HEAP: the core
# libraries' heap check; AP_SIM_TEST_SUPPORT_DIR: the helpers the profiles' end-to-end tests
# share (profile_sim_support.hpp).
if(NOT AP_PACKAGE_DATA_DIR)
  set(AP_FUZZ_KIT_DIR ${CMAKE_SOURCE_DIR}/fuzz/kit CACHE INTERNAL "")
  set(AP_CHECK_NO_HEAP ${CMAKE_SOURCE_DIR}/ci/check-no-heap)
  set(AP_SIM_TEST_SUPPORT_DIR ${CMAKE_SOURCE_DIR}/properties/sim)
endif()
option(AP_CFL_CHECK "Register the ctest that runs .clusterfuzzlite/build.sh locally (clang builds)" ON)
option(AP_FUZZ_BINARIES "Build the libFuzzer binaries fuzz_<name> in a non-fuzz preset (clang)" OFF)
if(AP_FUZZ_BINARIES AND NOT AP_FUZZ AND NOT AP_MCU_ONLY)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "AP_FUZZ_BINARIES needs clang (libFuzzer)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
set(AP_CORE_FLAGS -fno-exceptions -fno-rtti)
set(AP_CORE_LIBS "" CACHE INTERNAL "core libraries")
set(AP_CORE_HEADER_LIBS "" CACHE INTERNAL "header-only core libraries")

function(ap_core_library name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  foreach(dep IN LISTS A_DEPS)
    if(NOT dep IN_LIST AP_CORE_DEPS AND NOT dep IN_LIST AP_CORE_LIBS AND NOT dep IN_LIST AP_CORE_HEADER_LIBS)
      message(FATAL_ERROR "layer rule: core library ${name} may not depend on ${dep} (only core libraries and ${AP_CORE_DEPS})")
    endif()
  endforeach()
  add_library(${name} STATIC ${A_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_compile_options(${name} PRIVATE ${AP_CORE_FLAGS})
  target_link_libraries(${name} PUBLIC ${AP_CORE_DEPS} ${A_DEPS})
  add_custom_command(TARGET ${name} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -E env NM=${CMAKE_NM} ${AP_CHECK_NO_HEAP} $<TARGET_FILE:${name}>
    COMMENT "heap check: ${name}" VERBATIM)
  set(AP_CORE_LIBS ${AP_CORE_LIBS} ${name} CACHE INTERNAL "core libraries")
endfunction()

# A header-only core library (templates only): nothing to compile, so no archive for the
# heap check or the Cortex-M4 symbol check; its users' archives carry what it instantiates.
function(ap_core_header_library name)
  add_library(${name} INTERFACE)
  target_include_directories(${name} INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/include)
  set(AP_CORE_HEADER_LIBS ${AP_CORE_HEADER_LIBS} ${name} CACHE INTERNAL "header-only core libraries")
endfunction()

function(_ap_require_profile what)
  if(NOT AP_PROFILE)
    message(FATAL_ERROR "${what}: AP_PROFILE is not set in ${CMAKE_CURRENT_SOURCE_DIR} (docs/profiles.md)")
  endif()
endfunction()

function(ap_test_labels)
  cmake_parse_arguments(A "" "LABEL" "" ${ARGN})
  if(NOT A_LABEL MATCHES "^(unit|property|proof|fuzz|e2e)$")
    message(FATAL_ERROR "ap_test_labels: LABEL must be unit, property, proof, fuzz or e2e")
  endif()
  _ap_require_profile("${A_UNPARSED_ARGUMENTS}")
  set_tests_properties(${A_UNPARSED_ARGUMENTS} PROPERTIES LABELS "${A_LABEL};${AP_PROFILE}")
endfunction()

# One precompiled header for every test executable: GoogleTest, RapidCheck and the standard
# headers most tests include, parsed once per build instead of in each test object (measured:
# about 1 s of an 11 s object; docs/architecture.md). Defined on first use, with the tests' own
# definitions and libraries, so its flags are theirs.
function(_ap_test_pch)
  if(TARGET ap_test_pch)
    return()
  endif()
  file(CONFIGURE OUTPUT ${CMAKE_BINARY_DIR}/ap_test_pch.cpp CONTENT "// the precompiled header's own object\n")
  add_library(ap_test_pch OBJECT ${CMAKE_BINARY_DIR}/ap_test_pch.cpp)
  target_link_libraries(ap_test_pch PRIVATE rapidcheck_gtest rapidcheck GTest::gtest)
  target_compile_definitions(ap_test_pch PRIVATE AP_SOURCE_DIR="${CMAKE_SOURCE_DIR}" AP_BINARY_DIR="${CMAKE_BINARY_DIR}")
  target_precompile_headers(ap_test_pch PRIVATE <gtest/gtest.h> <rapidcheck.h> <rapidcheck/gtest.h> <algorithm>
                            <array> <cstdint> <cstdio> <cstdlib> <optional> <sstream> <string> <vector>)
endfunction()

function(ap_add_test name)
  if(AP_MCU_ONLY)
    return()
  endif()
  cmake_parse_arguments(A "" "LABEL" "SOURCES;LIBS" ${ARGN})
  if(NOT A_LABEL MATCHES "^(unit|property|proof|fuzz|e2e)$")
    message(FATAL_ERROR "ap_add_test(${name}): LABEL must be unit, property, proof, fuzz or e2e")
  endif()
  _ap_require_profile(${name})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS} rapidcheck_gtest rapidcheck GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE AP_SOURCE_DIR="${CMAKE_SOURCE_DIR}" AP_BINARY_DIR="${CMAKE_BINARY_DIR}")
  _ap_test_pch()
  target_precompile_headers(${name} REUSE_FROM ap_test_pch)
  gtest_discover_tests(${name} WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} DISCOVERY_TIMEOUT 60)
  # gtest_discover_tests flattens a list of labels into separate arguments, so the two labels
  # are set by a script ctest includes after the discovered tests (it lists them in
  # <name>_TESTS).
  set(_labels ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
  file(WRITE ${_labels} "foreach(_t IN LISTS ${name}_TESTS)\n"
                        "  set_tests_properties(\"\${_t}\" PROPERTIES LABELS \"${A_LABEL};${AP_PROFILE}\")\n"
                        "endforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${_labels})
endfunction()

function(ap_add_fuzz_target name)
  if(AP_MCU_ONLY)
    return()
  endif()
  cmake_parse_arguments(A "" "" "SOURCES;LIBS" ${ARGN})
  _ap_require_profile(${name})
  get_filename_component(_group ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  if(NOT AP_PROFILE_DIR)
    message(FATAL_ERROR "ap_add_fuzz_target(${name}): not in a profile's fuzz folder (fuzz/<profile>)")
  endif()
  set(_data ${AP_PROFILE_DIR})
  add_executable(replay_${name} ${A_SOURCES} ${AP_FUZZ_KIT_DIR}/src/replay_main.cpp)
  target_link_libraries(replay_${name} PRIVATE ${A_LIBS} ap_fuzz_kit)
  add_test(NAME fuzz.${name}.replay
           COMMAND replay_${name} ${_data}/corpus/${name} ${_data}/regressions/${name})
  set_tests_properties(fuzz.${name}.replay PROPERTIES LABELS "fuzz;${AP_PROFILE}")
  if(AP_FUZZ OR AP_FUZZ_BINARIES)
    add_executable(fuzz_${name} ${A_SOURCES})
    target_link_libraries(fuzz_${name} PRIVATE ${A_LIBS} ap_fuzz_kit)
    if(AP_FUZZ_ENGINE)
      separate_arguments(_engine UNIX_COMMAND "${AP_FUZZ_ENGINE}")
      target_link_options(fuzz_${name} PRIVATE ${_engine})
    else()
      target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
    endif()
    set_property(GLOBAL APPEND PROPERTY AP_FUZZ_TARGETS ${name})
    set(_fuzz_bin $<TARGET_FILE:fuzz_${name}>)
  else()
    set(_fuzz_bin -)
  endif()
  set_property(GLOBAL APPEND PROPERTY AP_FUZZ_LIST_LINES "${name}\t${_group}\t${_fuzz_bin}\t$<TARGET_FILE:replay_${name}>\t${AP_PROFILE}\t${_data}")
endfunction()

include(GoogleTest)

# ap_add_bench(<name> SOURCES ... [LIBS ...]): a Google Benchmark executable; its path is
# listed in <build>/benchmarks.txt, which `axisproof bench` runs.
function(ap_add_bench name)
  if(AP_MCU_ONLY)
    return()
  endif()
  cmake_parse_arguments(A "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS} benchmark::benchmark benchmark::benchmark_main)
  # Rates measured under a sanitizer mean nothing: the sanitizer builds (asan, fuzz) only build
  # a benchmark when asked by name, which keeps their full build (the gate's) shorter.
  if(AP_SANITIZE)
    set_target_properties(${name} PROPERTIES EXCLUDE_FROM_ALL ON)
  endif()
  set_property(GLOBAL APPEND PROPERTY AP_BENCHMARKS $<TARGET_FILE:${name}>)
  add_dependencies(benchmarks ${name})
endfunction()

# Written once the whole tree is configured (deferred to the end of the top-level directory).
function(_ap_write_lists)
  get_property(_lines GLOBAL PROPERTY AP_FUZZ_LIST_LINES)
  set(_text "")
  foreach(_l IN LISTS _lines)
    string(APPEND _text "${_l}\n")
  endforeach()
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/fuzz_targets.txt CONTENT "${_text}")
  set(_text "")
  foreach(_lib IN LISTS AP_CORE_LIBS)
    string(APPEND _text "${_lib}\t$<TARGET_FILE:${_lib}>\n")
  endforeach()
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/core_libs.txt CONTENT "${_text}")
  get_property(_images GLOBAL PROPERTY AP_FIRMWARE_IMAGES)
  string(REPLACE ";" "\n" _images "${_images}")
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/firmware_images.txt CONTENT "${_images}\n")
  # .clusterfuzzlite/build.sh must keep working with the standard OSS-Fuzz variables; this
  # runs it the way ClusterFuzzLite would, with the local clang and libFuzzer (asan and fuzz
  # presets; not in cov, which has no sanitizer).
  # Not in a project outside this tree: the check runs this tree's .clusterfuzzlite/build.sh.
  if(AP_CFL_CHECK AND CMAKE_CXX_COMPILER_ID MATCHES "Clang" AND (AP_SANITIZE OR AP_FUZZ)
     AND NOT AP_FUZZ_ENGINE AND _lines AND NOT AP_PACKAGE_DATA_DIR)
    add_test(NAME fuzz.clusterfuzzlite_build_sh
             COMMAND ${CMAKE_SOURCE_DIR}/ci/check-clusterfuzzlite ${CMAKE_BINARY_DIR}/cfl-check)
    set_tests_properties(fuzz.clusterfuzzlite_build_sh PROPERTIES LABELS fuzz TIMEOUT 900)
  endif()
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL _ap_write_lists)
