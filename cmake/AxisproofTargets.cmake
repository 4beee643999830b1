# Helper functions that give every layer the same shape.
#
#   ap_core_library(<name> SOURCES ... [DEPS ...])
#       A static library of the firmware core: no exceptions, no RTTI, and a post-build
#       check that no object references the heap (operator new/delete, malloc, free, ...).
#       DEPS may only name other core libraries or ap_codec (the layer rule).
#   ap_add_test(<name> LABEL <unit|property|proof|fuzz|e2e> SOURCES ... [LIBS ...])
#       A GoogleTest + RapidCheck executable whose tests ctest discovers with that label.
#   ap_add_fuzz_target(<name> SOURCES ... [LIBS ...])
#       In the fuzz preset: a libFuzzer binary fuzz_<name>. In every preset: a plain
#       replay driver replay_<name> and a ctest (label fuzz) that replays
#       fuzz/corpus/<name> and fuzz/regressions/<name>.

set(AP_CORE_FLAGS -fno-exceptions -fno-rtti)
set(AP_CORE_LIBS "" CACHE INTERNAL "core libraries")

function(ap_core_library name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  foreach(dep IN LISTS A_DEPS)
    if(NOT dep STREQUAL "ap_codec" AND NOT dep IN_LIST AP_CORE_LIBS)
      message(FATAL_ERROR "layer rule: core library ${name} may not depend on ${dep} (only core libraries and ap_codec)")
    endif()
  endforeach()
  add_library(${name} STATIC ${A_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_compile_options(${name} PRIVATE ${AP_CORE_FLAGS})
  target_link_libraries(${name} PUBLIC ap_codec ${A_DEPS})
  add_custom_command(TARGET ${name} POST_BUILD
    COMMAND ${CMAKE_SOURCE_DIR}/ci/check-no-heap $<TARGET_FILE:${name}>
    COMMENT "heap check: ${name}" VERBATIM)
  set(AP_CORE_LIBS ${AP_CORE_LIBS} ${name} CACHE INTERNAL "core libraries")
endfunction()

function(ap_add_test name)
  cmake_parse_arguments(A "" "LABEL" "SOURCES;LIBS" ${ARGN})
  if(NOT A_LABEL MATCHES "^(unit|property|proof|fuzz|e2e)$")
    message(FATAL_ERROR "ap_add_test(${name}): LABEL must be unit, property, proof, fuzz or e2e")
  endif()
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS} rapidcheck_gtest rapidcheck GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE AP_SOURCE_DIR="${CMAKE_SOURCE_DIR}" AP_BINARY_DIR="${CMAKE_BINARY_DIR}")
  gtest_discover_tests(${name} PROPERTIES LABELS ${A_LABEL}
                       WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} DISCOVERY_TIMEOUT 60)
endfunction()

function(ap_add_fuzz_target name)
  cmake_parse_arguments(A "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(replay_${name} ${A_SOURCES} ${CMAKE_SOURCE_DIR}/fuzz/replay_main.cpp)
  target_link_libraries(replay_${name} PRIVATE ${A_LIBS})
  add_test(NAME fuzz.${name}.replay
           COMMAND replay_${name} ${CMAKE_SOURCE_DIR}/fuzz/corpus/${name} ${CMAKE_SOURCE_DIR}/fuzz/regressions/${name})
  set_tests_properties(fuzz.${name}.replay PROPERTIES LABELS fuzz)
  if(AP_FUZZ)
    add_executable(fuzz_${name} ${A_SOURCES})
    target_link_libraries(fuzz_${name} PRIVATE ${A_LIBS})
    target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
    set_property(GLOBAL APPEND PROPERTY AP_FUZZ_TARGETS ${name})
  endif()
endfunction()

include(GoogleTest)

# ap_add_bench(<name> SOURCES ... [LIBS ...]): a Google Benchmark executable; its path is
# listed in <build>/benchmarks.txt, which `axisproof bench` runs.
function(ap_add_bench name)
  cmake_parse_arguments(A "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS} benchmark::benchmark benchmark::benchmark_main)
  set_property(GLOBAL APPEND PROPERTY AP_BENCHMARKS $<TARGET_FILE:${name}>)
endfunction()
