# Installable CMake package: find_package(anyphys) gives anyphys::anyphys (all built backends)
# and anyphys::<backend> per backend.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(DIRECTORY api/include/ listeners/include/ containers/include/ fields/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
set_target_properties(anyphys_headers PROPERTIES EXPORT_NAME headers)
install(TARGETS anyphys anyphys_headers ${ANYPHYS_BACKEND_TARGETS}
        EXPORT anyphysTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT anyphysTargets NAMESPACE anyphys:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/anyphys)

set(ANYPHYS_INSTALLED_BACKENDS "${ANYPHYS_BACKENDS}")
configure_package_config_file(cmake/anyphysConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/anyphysConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/anyphys)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/anyphysConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/anyphysConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/anyphysConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/anyphys)
