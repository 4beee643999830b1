# ap_add_all_subdirs([EXCEPT name...]): add every sub-folder that has a CMakeLists.txt, in
# name order, except the declared profiles' folders (ap_add_profile_dirs adds those, with
# their label) and the names given.
function(ap_add_all_subdirs)
  cmake_parse_arguments(A "" "" "EXCEPT" ${ARGN})
  get_property(_profiles GLOBAL PROPERTY AP_PROFILES)
  file(GLOB _dirs LIST_DIRECTORIES true CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*)
  foreach(_d ${_dirs})
    get_filename_component(_n ${_d} NAME)
    if(EXISTS ${_d}/CMakeLists.txt AND NOT _n IN_LIST _profiles AND NOT _n IN_LIST A_EXCEPT)
      add_subdirectory(${_d})
    endif()
  endforeach()
endfunction()
