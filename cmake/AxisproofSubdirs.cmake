# ap_add_subdirs(<dir>...): add each listed sub-folder that has a CMakeLists.txt, in the
# order given (the order is the dependency order inside a layer or a profile's folder).
# Which profiles' folders a build takes is ap_add_profile_dirs's business
# (cmake/AxisproofProfiles.cmake).
macro(ap_add_subdirs)
  foreach(_d ${ARGN})
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${_d}/CMakeLists.txt)
      add_subdirectory(${_d})
    endif()
  endforeach()
endmacro()
