include(CMakePackageConfigHelpers)

set(CBR_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/cbr")
set(CBR_FMOD_DIR "${CMAKE_INSTALL_INCLUDEDIR}/cbr/fortran")

install(TARGETS cbr EXPORT cbrTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES include/cbr/cbr.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/cbr)
install(EXPORT cbrTargets NAMESPACE cbr:: DESTINATION ${CBR_CMAKE_DIR})

configure_package_config_file(cmake/cbrConfig.cmake.in
  "${CMAKE_CURRENT_BINARY_DIR}/cbrConfig.cmake"
  INSTALL_DESTINATION ${CBR_CMAKE_DIR})
write_basic_package_version_file("${CMAKE_CURRENT_BINARY_DIR}/cbrConfigVersion.cmake"
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/cbrConfig.cmake"
              "${CMAKE_CURRENT_BINARY_DIR}/cbrConfigVersion.cmake"
        DESTINATION ${CBR_CMAKE_DIR})

# pkg-config: absolute paths, whatever form the install dirs were given in.
foreach(_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_dir}}")
    set(CBR_PC_${_dir} "${CMAKE_INSTALL_${_dir}}")
  else()
    set(CBR_PC_${_dir} "\${prefix}/${CMAKE_INSTALL_${_dir}}")
  endif()
endforeach()
set(CBR_PC_FMODDIR "\${includedir}/cbr/fortran")
configure_file(pkgconfig/cbr.pc.in "${CMAKE_CURRENT_BINARY_DIR}/cbr.pc" @ONLY)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/cbr.pc" DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
