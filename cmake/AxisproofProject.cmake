# The two calls a project makes after its declarations, in this tree (cli/CMakeLists.txt) and in
# a firmware team's own repository (docs/profiles.md "Your own firmware"):
#
#   ap_add_profiles()
#       For a project whose tree holds only profile folders (no layer CMakeLists.txt of its
#       own): adds every <layer>/<name> folder of every declared profile that has a
#       CMakeLists.txt, layer by layer in the harness's order (AP_BUILD_LAYERS), each with
#       AP_PROFILE, AP_PROFILE_DIR and AP_PROFILE_ROOT set as ap_add_profile_dirs() sets them and
#       its build folder <build>/<layer>/<name>. The code layers (protocol to sim) get
#       AP_LAYER_OPTIONS, as in the harness's tree; <build>/benchmarks.txt lists the profiles'
#       benchmarks (ap_add_bench) for `axisproof bench`.
#   ap_add_axisproof([<name>])
#       The command line (default name axisproof): the shared commands and main() (the
#       library ap_cli), each declared profile's adapters (ap_<profile>_cli) and the profile
#       table generated from the declarations (<build>/declared_profiles/profiles.cpp). The tree it works
#       on (scenarios, build/<preset>, out/) is the calling project's top folder.

# The harness's layers in dependency order (its top CMakeLists.txt adds them so); the first six
# hold the code under test and its models, which AP_LAYER_OPTIONS compiles.
set(AP_BUILD_LAYERS protocol core firmware models pc sim properties fuzz bench cli)
set(AP_CODE_LAYERS protocol core firmware models pc sim)
# The CLI's process plumbing (source_dir() is the tree of the executable that compiles it).
if(NOT AP_PACKAGE_DATA_DIR)
  set(AP_CLI_PROCESS_SOURCE ${CMAKE_SOURCE_DIR}/cli/process.cpp)
endif()

function(ap_add_profiles)
  enable_testing()
  get_directory_property(_options COMPILE_OPTIONS)
  set(AP_MODEL_LIBS "" CACHE INTERNAL "model libraries")
  foreach(_layer IN LISTS AP_BUILD_LAYERS)
    if(_layer IN_LIST AP_CODE_LAYERS)
      set_directory_properties(PROPERTIES COMPILE_OPTIONS "${_options};${AP_LAYER_OPTIONS}")
    else()
      set_directory_properties(PROPERTIES COMPILE_OPTIONS "${_options}")
    endif()
    if(_layer STREQUAL "bench" AND NOT TARGET benchmarks)
      add_custom_target(benchmarks)
    endif()
    _ap_add_profile_layer(${_layer} ${CMAKE_BINARY_DIR}/${_layer})
  endforeach()
  set_directory_properties(PROPERTIES COMPILE_OPTIONS "${_options}")
  get_property(_benches GLOBAL PROPERTY AP_BENCHMARKS)
  list(JOIN _benches "\n" _text)
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/benchmarks.txt CONTENT "${_text}\n")
endfunction()

function(ap_add_axisproof)
  set(_name axisproof)
  if(ARGC GREATER 0)
    set(_name ${ARGV0})
  endif()
  set(_table ${CMAKE_BINARY_DIR}/declared_profiles/profiles.cpp)
  set_source_files_properties(${_table} PROPERTIES GENERATED TRUE SKIP_UNITY_BUILD_INCLUSION TRUE)
  add_executable(${_name} ${AP_CLI_PROCESS_SOURCE} ${_table})
  # Adapters first, then the shared commands they call back into (sim_run_main, host_boards).
  get_property(_profiles GLOBAL PROPERTY AP_PROFILES)
  foreach(_p IN LISTS _profiles)
    if(TARGET ap_${_p}_cli)
      target_link_libraries(${_name} PRIVATE ap_${_p}_cli)
    endif()
  endforeach()
  target_link_libraries(${_name} PRIVATE ap_cli)
  target_compile_definitions(${_name} PRIVATE AP_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
endfunction()
