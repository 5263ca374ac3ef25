# The version is written once, in project(); the public header repeats it as
# macros for the C preprocessor. Refuse to configure if they disagree.
file(READ "${CMAKE_CURRENT_SOURCE_DIR}/include/cbr/cbr.h" _cbr_header)
foreach(_part MAJOR MINOR PATCH)
  string(REGEX MATCH "#define CBR_VERSION_${_part} ([0-9]+)" _m "${_cbr_header}")
  set(_header_${_part} "${CMAKE_MATCH_1}")
endforeach()
set(_header_version "${_header_MAJOR}.${_header_MINOR}.${_header_PATCH}")
if(NOT _header_version STREQUAL PROJECT_VERSION)
  message(FATAL_ERROR "include/cbr/cbr.h says version ${_header_version}, CMakeLists.txt says ${PROJECT_VERSION}")
endif()
