# SPDX-License-Identifier: MIT
# Every dependency comes from a Debian 12 package (scripts/install-deps.sh installs them).
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(nlohmann_json REQUIRED)
pkg_check_modules(MODBUS REQUIRED IMPORTED_TARGET libmodbus)
pkg_check_modules(GPIOD REQUIRED IMPORTED_TARGET libgpiod libgpiodcxx)
if(HIL_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(HIL_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# Standalone Asio (libasio-dev) is header only.
find_path(ASIO_INCLUDE_DIR asio.hpp REQUIRED)
add_library(hil_asio INTERFACE)
target_include_directories(hil_asio SYSTEM INTERFACE ${ASIO_INCLUDE_DIR})
# ASIO_DISABLE_STD_ALIGNED_ALLOC: Asio picks its aligned allocator from libstdc++ macros, so a file
# that includes Asio before any standard header would otherwise pair new/delete differently from
# the others (ASan reports alloc-dealloc-mismatch).
target_compile_definitions(hil_asio INTERFACE ASIO_STANDALONE ASIO_NO_DEPRECATED ASIO_DISABLE_STD_ALIGNED_ALLOC)
target_link_libraries(hil_asio INTERFACE Threads::Threads)
add_library(hil::asio ALIAS hil_asio)
