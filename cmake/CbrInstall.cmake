include(CMakePackageConfigHelpers)

set(CBR_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/cbr")
set(CBR_FMOD_DIR "${CMAKE_INSTALL_INCLUDEDIR}/cbr/fortran")

install(TARGETS cbr EXPORT cbrTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(TARGET cbr_fortran_module)
  install(TARGETS cbr_fortran_module EXPORT cbrTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
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
# The files are written at install time, so that prefix= is where they are
# installed (`cmake --install build --prefix P` gives prefix=P, not the
# CMAKE_INSTALL_PREFIX of configure time).
foreach(_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_dir}}")
    set(CBR_PC_${_dir} "${CMAKE_INSTALL_${_dir}}")
  else()
    set(CBR_PC_${_dir} "\${prefix}/${CMAKE_INSTALL_${_dir}}")
  endif()
endforeach()
set(CBR_PC_FMODDIR "\${includedir}/cbr/fortran")
set(_cbr_pc_files cbr)
if(TARGET cbr_fortran_module)
  list(APPEND _cbr_pc_files cbr-fortran)
endif()
foreach(_pc IN LISTS _cbr_pc_files)
  install(CODE "
    set(PROJECT_VERSION [[${PROJECT_VERSION}]])
    set(CBR_PC_LIBDIR [[${CBR_PC_LIBDIR}]])
    set(CBR_PC_INCLUDEDIR [[${CBR_PC_INCLUDEDIR}]])
    set(CBR_PC_FMODDIR [[${CBR_PC_FMODDIR}]])
    configure_file([[${CMAKE_CURRENT_SOURCE_DIR}/pkgconfig/${_pc}.pc.in]]
                   [[${CMAKE_CURRENT_BINARY_DIR}/pkgconfig/${_pc}.pc]] @ONLY)")
  install(FILES "${CMAKE_CURRENT_BINARY_DIR}/pkgconfig/${_pc}.pc"
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()
