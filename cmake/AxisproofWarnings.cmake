# Project-wide compiler flags. Warnings are errors in dev/asan/release; sanitizers and
# coverage are switched on per preset, for every target alike, so tests and code under
# test are instrumented the same way.
add_compile_options(-Wall -Wextra -Wshadow -Wconversion -Wsign-conversion -Wcast-align -Wunused -Wpedantic
                    -Wnull-dereference -Wimplicit-fallthrough
                    # C++-only warnings; the C files (idlc's generated DDS types) would print notices.
                    $<$<COMPILE_LANGUAGE:CXX>:-Wnon-virtual-dtor>
                    $<$<COMPILE_LANGUAGE:CXX>:-Wold-style-cast>
                    $<$<COMPILE_LANGUAGE:CXX>:-Woverloaded-virtual>)
if(AP_WERROR)
  add_compile_options(-Werror)
endif()
if(AP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined -fno-sanitize-recover=all)
endif()
if(AP_COVERAGE)
  add_compile_options(-fprofile-instr-generate -fcoverage-mapping)
  add_link_options(-fprofile-instr-generate)
endif()
if(AP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "AP_FUZZ needs clang (libFuzzer)")
  endif()
  # Every object gets coverage edges for libFuzzer; only fuzz executables link the engine.
  # With an external engine (.clusterfuzzlite/build.sh) the instrumentation comes from $CXXFLAGS.
  if(NOT AP_FUZZ_ENGINE)
    add_compile_options(-fsanitize=fuzzer-no-link)
  endif()
  # Fuzzing-only switch: lets targets that opt in skip the frame CRC check (see fuzz/README.md).
  add_compile_definitions(AP_FUZZING_BUILD=1)
endif()
