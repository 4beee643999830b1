# A firmware profile declares itself once (docs/profiles.md "The declaration"):
#
#   ap_declare_profile(<name>
#     TITLE "<controller>" SEED "<where its requirements come from>"
#     MCU "<target and budget, in words>" FLASH_BUDGET <bytes> RAM_BUDGET <bytes>
#     STATE_SYMBOL <symbol> STATE_OBJECT <type>   # the object whose size the size check adds
#     [SIZE_TAG <tag>] [DEFAULT] [USES <shared folder>...])
#
# Its folders are not listed: they are every <layer>/<name> folder that exists (AP_LAYER_DIRS
# below), so a profile's code is found where its name says and nowhere else. USES names the
# shared folders its firmware builds on (coverage and the cross build take them too).
# The declaration's output, written at the end of configuring (<build>/declared_profiles/):
#   profiles.tsv      one line per profile: name, title, seed, mcu, size tag, default (0/1),
#                     its folders, its coverage folders, its mutants folder (';'-separated lists)
#   <name>.env        the same for shell scripts (ci/m4-build, ci/mutate): AP_PROFILE_* variables
#   profiles.cpp      the CLI's profile table: each profile's adapter (cli/<name>/) with the
#                     declared fields filled in
# Every layer's CMakeLists.txt calls ap_add_profile_dirs() after its shared folders; with
# AP_MCU_ONLY only AP_MCU_PROFILE's folders are added.
#
# A profile outside this tree (docs/profiles.md "Your own firmware") declares itself the same
# way after find_package(axisproof); ROOT is then its own source folder.

set(AP_LAYER_DIRS core protocol firmware models pc sim properties fuzz bench cli scenarios ci/mutants ci/gate-times)
# The folders whose code is the profile's firmware and PC program: what the gate's coverage
# figure measures (with USES) and what the cross build compiles (without pc).
set(AP_COVERAGE_LAYERS core protocol pc)

function(ap_declare_profile name)
  cmake_parse_arguments(A "DEFAULT" "TITLE;SEED;MCU;FLASH_BUDGET;RAM_BUDGET;STATE_SYMBOL;STATE_OBJECT;SIZE_TAG;ROOT" "USES" ${ARGN})
  if(NOT name MATCHES "^[a-z][a-z0-9]*$")
    message(FATAL_ERROR "ap_declare_profile(${name}): a profile's name is lower-case letters and digits")
  endif()
  get_property(_known GLOBAL PROPERTY AP_PROFILES)
  if(name IN_LIST _known)
    message(FATAL_ERROR "ap_declare_profile(${name}): declared twice")
  endif()
  foreach(_k TITLE SEED MCU FLASH_BUDGET RAM_BUDGET STATE_SYMBOL STATE_OBJECT)
    if(NOT A_${_k})
      message(FATAL_ERROR "ap_declare_profile(${name}): ${_k} is required")
    endif()
  endforeach()
  if(NOT A_ROOT)
    set(A_ROOT ${CMAKE_SOURCE_DIR})
  endif()
  if(NOT A_SIZE_TAG)
    set(A_SIZE_TAG m4-${name})
  endif()
  set(_dirs "")
  set(_cov "")
  foreach(_l IN LISTS AP_LAYER_DIRS)
    if(IS_DIRECTORY ${A_ROOT}/${_l}/${name})
      list(APPEND _dirs ${_l}/${name})
      if(_l IN_LIST AP_COVERAGE_LAYERS)
        list(APPEND _cov ${_l}/${name})
      endif()
    endif()
  endforeach()
  foreach(_u IN LISTS A_USES)
    # AP_PACKAGE_SHARED_DIRS: the harness's shared folders an installed package brings
    # (axisproofConfig.cmake).
    if(NOT IS_DIRECTORY ${CMAKE_SOURCE_DIR}/${_u} AND NOT IS_DIRECTORY ${A_ROOT}/${_u}
       AND NOT _u IN_LIST AP_PACKAGE_SHARED_DIRS)
      message(FATAL_ERROR "ap_declare_profile(${name}): USES ${_u}: no such folder")
    endif()
    list(APPEND _cov ${_u})
  endforeach()
  set_property(GLOBAL APPEND PROPERTY AP_PROFILES ${name})
  foreach(_k TITLE SEED MCU FLASH_BUDGET RAM_BUDGET STATE_SYMBOL STATE_OBJECT SIZE_TAG ROOT USES DEFAULT)
    set_property(GLOBAL PROPERTY AP_PROFILE_${name}_${_k} "${A_${_k}}")
  endforeach()
  set_property(GLOBAL PROPERTY AP_PROFILE_${name}_DIRS "${_dirs}")
  set_property(GLOBAL PROPERTY AP_PROFILE_${name}_COVERAGE "${_cov}")
endfunction()

# The profiles this build configures: all of them, or AP_MCU_PROFILE alone in the cross build.
function(ap_profiles_of_this_build out)
  get_property(_all GLOBAL PROPERTY AP_PROFILES)
  if(AP_MCU_ONLY)
    set(_all ${AP_MCU_PROFILE})
  endif()
  set(${out} ${_all} PARENT_SCOPE)
endfunction()

# In a layer's CMakeLists.txt: add <layer>/<profile> for every profile that has one, with
# AP_PROFILE set to the profile (its tests and fuzz targets carry that label),
# AP_PROFILE_DIR to the folder (where its fuzz targets keep their corpora) and AP_PROFILE_ROOT
# to the profile's ROOT. A project without layer CMakeLists.txt files calls ap_add_profiles()
# instead (cmake/AxisproofProject.cmake).
function(ap_add_profile_dirs)
  file(RELATIVE_PATH _layer ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  _ap_add_profile_layer(${_layer} ${CMAKE_CURRENT_BINARY_DIR})
endfunction()

# <layer>/<profile> of every profile of this build that has one, its binary folder under
# <binary_base>/<profile> (the tree's own folders keep their usual binary folder).
function(_ap_add_profile_layer layer binary_base)
  ap_profiles_of_this_build(_profiles)
  foreach(_p IN LISTS _profiles)
    get_property(_root GLOBAL PROPERTY AP_PROFILE_${_p}_ROOT)
    set(_d ${_root}/${layer}/${_p})
    if(EXISTS ${_d}/CMakeLists.txt)
      set(AP_PROFILE ${_p})
      set(AP_PROFILE_DIR ${_d})
      # The top of the profile's tree (its declaration's ROOT): where its folders find each
      # other (scenarios/<name> from properties/<name>) inside this tree and outside it.
      set(AP_PROFILE_ROOT ${_root})
      if(_root STREQUAL CMAKE_SOURCE_DIR AND binary_base STREQUAL CMAKE_CURRENT_BINARY_DIR)
        add_subdirectory(${_d})
      else()
        add_subdirectory(${_d} ${binary_base}/${_p})
      endif()
    endif()
  endforeach()
endfunction()

function(_ap_cpp_string out text)
  string(REPLACE "\\" "\\\\" text "${text}")
  string(REPLACE "\"" "\\\"" text "${text}")
  set(${out} "\"${text}\"" PARENT_SCOPE)
endfunction()

# The items as the elements of a C++ braced list of strings ("a", "b", ).
function(_ap_cpp_list out)
  set(_text "")
  foreach(_i IN LISTS ARGN)
    _ap_cpp_string(_q "${_i}")
    string(APPEND _text "${_q}, ")
  endforeach()
  set(${out} "${_text}" PARENT_SCOPE)
endfunction()

# Written once the whole tree is configured (deferred to the end of the top-level directory).
function(_ap_write_profiles)
  get_property(_profiles GLOBAL PROPERTY AP_PROFILES)
  set(_tsv "")
  set(_decls "")
  set(_entries "")
  foreach(_p IN LISTS _profiles)
    foreach(_k TITLE SEED MCU FLASH_BUDGET RAM_BUDGET STATE_SYMBOL STATE_OBJECT SIZE_TAG DIRS COVERAGE DEFAULT ROOT)
      get_property(_${_k} GLOBAL PROPERTY AP_PROFILE_${_p}_${_k})
    endforeach()
    if(_DEFAULT)
      set(_DEFAULT 1)
    else()
      set(_DEFAULT 0)
    endif()
    string(APPEND _tsv "${_p}\t${_TITLE}\t${_SEED}\t${_MCU}\t${_SIZE_TAG}\t${_DEFAULT}\t${_DIRS}\t${_COVERAGE}\t${_ROOT}/ci/mutants/${_p}\n")
    string(REPLACE ";" " " _dirs_sh "${_DIRS}")
    string(REPLACE ";" " " _cov_sh "${_COVERAGE}")
    file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/declared_profiles/${_p}.env CONTENT
"AP_PROFILE_NAME='${_p}'
AP_PROFILE_MCU='${_MCU}'
AP_PROFILE_FLASH_BUDGET=${_FLASH_BUDGET}
AP_PROFILE_RAM_BUDGET=${_RAM_BUDGET}
AP_PROFILE_STATE_SYMBOL='${_STATE_SYMBOL}'
AP_PROFILE_STATE_OBJECT='${_STATE_OBJECT}'
AP_PROFILE_SIZE_TAG='${_SIZE_TAG}'
AP_PROFILE_ROOT='${_ROOT}'
AP_PROFILE_DIRS='${_dirs_sh}'
AP_PROFILE_COVERAGE='${_cov_sh}'
")
    if(TARGET ap_${_p}_cli)
      string(APPEND _decls "Profile ap_profile_${_p}();\n")
      _ap_cpp_string(_t "${_TITLE}")
      _ap_cpp_string(_s "${_SEED}")
      _ap_cpp_string(_m "${_MCU}")
      _ap_cpp_string(_g "${_SIZE_TAG}")
      _ap_cpp_list(_covs ${_COVERAGE})
      _ap_cpp_list(_ds ${_DIRS})
      string(APPEND _entries "    declared(ap_profile_${_p}(), \"${_p}\", ${_t}, ${_s}, ${_m}, ${_g}, ${_DEFAULT}, {${_ds}}, {${_covs}}),\n")
    endif()
  endforeach()
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/declared_profiles/profiles.tsv CONTENT "${_tsv}")
  if(NOT AP_MCU_ONLY)
    file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/declared_profiles/profiles.cpp CONTENT
"// Generated from the profiles' declarations (cmake/AxisproofProfiles.cmake); not in the tree.
#include \"profile.hpp\"

namespace ap::cli {

${_decls}
const std::vector<Profile>& profiles() {
  static const std::vector<Profile> all = {
${_entries}  };
  return all;
}

}  // namespace ap::cli
")
  endif()
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL _ap_write_profiles)
