# <build>/targets.tsv: every target this build defines, the folder that defines it and what it
# links, written once the whole tree is configured. ci/check-architecture reads it to hold the
# real link graph to the layer table of docs/architecture.md: a target's layer is the first
# component of its folder, so the file needs the folder, not a name convention.
#
# One line per target, tab-separated:
#   name  type  folder  links  interface-links
# folder: the target's SOURCE_DIR from the top of the tree (a profile declared outside the tree,
# docs/profiles.md "Your own firmware": from the top of its ROOT, which has the same layer
# folders; anything else stays absolute). links / interface-links: the target's LINK_LIBRARIES
# and INTERFACE_LINK_LIBRARIES as target_link_libraries left them (';'-separated, generator
# expressions unevaluated); the checker keeps the items that name a target.
# Included by properties/layout/CMakeLists.txt, beside the ctests that read the file.
include_guard(GLOBAL)

function(_ap_targets_of_dir dir out)
  get_property(_targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(_subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(_d IN LISTS _subdirs)
    _ap_targets_of_dir(${_d} _more)
    list(APPEND _targets ${_more})
  endforeach()
  set(${out} ${_targets} PARENT_SCOPE)
endfunction()

function(_ap_write_target_list)
  _ap_targets_of_dir(${CMAKE_SOURCE_DIR} _targets)
  set(_roots ${CMAKE_SOURCE_DIR})
  get_property(_profiles GLOBAL PROPERTY AP_PROFILES)
  foreach(_p IN LISTS _profiles)
    get_property(_r GLOBAL PROPERTY AP_PROFILE_${_p}_ROOT)
    if(_r)
      list(APPEND _roots ${_r})
    endif()
  endforeach()
  set(_text "")
  foreach(_t IN LISTS _targets)
    get_target_property(_type ${_t} TYPE)
    get_target_property(_dir ${_t} SOURCE_DIR)
    foreach(_r IN LISTS _roots)
      cmake_path(IS_PREFIX _r "${_dir}" NORMALIZE _inside)
      if(_inside)
        cmake_path(RELATIVE_PATH _dir BASE_DIRECTORY ${_r})
        break()
      endif()
    endforeach()
    set(_links "")
    if(NOT _type STREQUAL "INTERFACE_LIBRARY" AND NOT _type STREQUAL "UTILITY")
      get_target_property(_links ${_t} LINK_LIBRARIES)
    endif()
    get_target_property(_iface ${_t} INTERFACE_LINK_LIBRARIES)
    foreach(_v _links _iface)
      if(NOT ${_v})
        set(${_v} "")
      endif()
      string(REPLACE "\t" " " ${_v} "${${_v}}")
      string(REPLACE "\n" " " ${_v} "${${_v}}")
    endforeach()
    string(APPEND _text "${_t}\t${_type}\t${_dir}\t${_links}\t${_iface}\n")
  endforeach()
  # Replaced only when it changes, so a reconfigure leaves its time stamp alone.
  file(WRITE ${CMAKE_BINARY_DIR}/targets.tsv.new "${_text}")
  file(COPY_FILE ${CMAKE_BINARY_DIR}/targets.tsv.new ${CMAKE_BINARY_DIR}/targets.tsv ONLY_IF_DIFFERENT)
  file(REMOVE ${CMAKE_BINARY_DIR}/targets.tsv.new)
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL _ap_write_target_list)
