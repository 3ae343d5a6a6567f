# SPDX-License-Identifier: MIT
# `cmake --install` and `cpack -G DEB`. Two components:
#   runtime  bin/hilbridge and its data under share/hilbridge/ (device profiles, Modbus register
#            profiles, EDS files, examples), found relative to the executable (hil::data_dirs), so
#            the installed tree may be moved anywhere;
#   dev      the public headers, the static hil_* libraries, the exported CMake package
#            (find_package(hilbridge) -> hil::core, hil::runtime, ...) and hilbridge.pc.
# Included last from the top-level CMakeLists.txt, after every area has declared its libraries.
include(CMakePackageConfigHelpers)

install(TARGETS hilbridge RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
set(hil_data_dir ${CMAKE_INSTALL_DATADIR}/hilbridge)
# The layout under share/hilbridge/ mirrors the source tree, so hil::data_dirs("profiles/modbus")
# finds <prefix>/share/hilbridge/profiles/modbus installed and <source>/profiles/modbus in a build tree.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/profiles/devices DESTINATION ${hil_data_dir}/profiles
        COMPONENT runtime PATTERN "tools" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/profiles/modbus ${PROJECT_SOURCE_DIR}/profiles/canopen
        DESTINATION ${hil_data_dir}/profiles COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples DESTINATION ${hil_data_dir} COMPONENT runtime)

# Interface targets the exported libraries link publicly.
set_target_properties(hil_asio PROPERTIES EXPORT_NAME asio)
install(TARGETS hil_asio EXPORT hilbridgeTargets COMPONENT dev)

set(hil_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/hilbridge)
install(EXPORT hilbridgeTargets NAMESPACE hil:: DESTINATION ${hil_cmake_dir} COMPONENT dev)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/hilbridgeConfig.cmake.in
  ${PROJECT_BINARY_DIR}/hilbridgeConfig.cmake INSTALL_DESTINATION ${hil_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hilbridgeConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hilbridgeConfig.cmake ${PROJECT_BINARY_DIR}/hilbridgeConfigVersion.cmake
        DESTINATION ${hil_cmake_dir} COMPONENT dev)

# pkg-config: the static libraries in one link group (their order does not matter then).
get_property(hil_libs GLOBAL PROPERTY HIL_INSTALLED_LIBRARIES)
set(HIL_PC_LIBS "")
foreach(lib IN LISTS hil_libs)
  string(APPEND HIL_PC_LIBS " -l${lib}")
endforeach()
# Relocatable: the prefix is found from the .pc file's own place.
file(RELATIVE_PATH HIL_PC_UP /p/${CMAKE_INSTALL_LIBDIR}/pkgconfig /p)
string(REGEX REPLACE "/$" "" HIL_PC_UP "${HIL_PC_UP}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/hilbridge.pc.in ${PROJECT_BINARY_DIR}/hilbridge.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/hilbridge.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)

# cpack -G DEB: hilbridge_<version>_<arch>.deb (runtime; its dependencies computed by
# dpkg-shlibdeps from the executable) and hilbridge-dev_<version>_<arch>.deb.
set(CPACK_PACKAGE_NAME hilbridge)
set(CPACK_PACKAGE_VENDOR "hilbridge")
set(CPACK_PACKAGE_CONTACT "hilbridge maintainers <hilbridge@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Hardware-in-the-loop bridge to fieldbus drives (CANopen, Modbus/TCP, step/dir, serial)")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME hilbridge)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION electronics)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_DEV_PACKAGE_NAME hilbridge-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "hilbridge (= ${PROJECT_VERSION}), libyaml-cpp-dev, libfmt-dev, nlohmann-json3-dev, libasio-dev, libmodbus-dev, libgpiod-dev, pkg-config")
set(CPACK_COMPONENT_RUNTIME_DESCRIPTION "the hilbridge command and its device profiles, EDS files and examples")
set(CPACK_COMPONENT_DEV_DESCRIPTION "headers, static libraries, CMake package and pkg-config file of hilbridge")
include(CPack)
