# Installs the libraries, headers, CLI and bundled maps, and exports gridloc::* targets for
# find_package(gridloc).
include(CMakePackageConfigHelpers)

install(TARGETS gridloc_grids gridloc_sensors gridloc_engine gridloc_evaluation EXPORT gridlocTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The OctoMap reader is a component of its own: find_package(gridloc COMPONENTS octomap).
install(TARGETS gridloc_octomap EXPORT gridlocOctomapTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(module grids sensors engine)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
if(GRIDLOC_BUILD_EXAMPLES)
  install(TARGETS gridloc RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/maps/ DESTINATION ${CMAKE_INSTALL_DATADIR}/gridloc/maps
        FILES_MATCHING PATTERN "*.yaml" PATTERN "*.pgm" PATTERN "*.png")

install(EXPORT gridlocTargets NAMESPACE gridloc:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gridloc)
install(EXPORT gridlocOctomapTargets NAMESPACE gridloc::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gridloc)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gridlocConfig.cmake.in
  ${PROJECT_BINARY_DIR}/gridlocConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gridloc)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/gridlocConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/gridlocConfig.cmake ${PROJECT_BINARY_DIR}/gridlocConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gridloc)
