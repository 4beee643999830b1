# ap_add_subdirs(<dir>...): add each listed sub-folder that has a CMakeLists.txt, in the
# order given (the order is the dependency order inside a layer).
# With AP_MCU_ONLY (the m4 preset) only the folders of AP_MCU_PROFILE (AP_MCU_DIRS_<profile>,
# top-level CMakeLists.txt) are added.
macro(ap_add_subdirs)
  foreach(_d ${ARGN})
    file(RELATIVE_PATH _rel ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/${_d})
    if(AP_MCU_ONLY AND NOT _rel MATCHES "^(${AP_MCU_DIRS_${AP_MCU_PROFILE}})(/|$)")
      continue()
    endif()
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${_d}/CMakeLists.txt)
      add_subdirectory(${_d})
    endif()
  endforeach()
endmacro()
