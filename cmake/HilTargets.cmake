# SPDX-License-Identifier: MIT
include(GNUInstallDirs)
# Helpers shared by every area. An area never edits a file outside its own folders:
# it calls these from its own CMakeLists.txt.

# Warnings and sanitizers travel through one interface target.
add_library(hil_warnings INTERFACE)
target_compile_options(hil_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
  -Wno-sign-conversion $<$<BOOL:${HIL_WERROR}>:-Werror>)
if(HIL_SANITIZE)
  # -Wno-stringop-overflow: with ASan's instrumentation g++ 12 loses the bounds of libstdc++'s
  # std::fill inside std::vector::resize at -O1 and above and reports a memset of 2^64 - 8 bytes
  # on a path that cannot run (first seen on a shrinking resize in sdo_server.cpp, now an erase).
  # The plain -O2 build (HIL_CI_FULL=1, the demo) keeps the warning; ASan checks every access of
  # this build at run time.
  # -fno-sanitize=vptr: the vptr check probes the object's memory through a pipe (libsanitizer's
  # IsAccessibleMemoryRange), so in a process that has used up its descriptors (the EMFILE tests of
  # the TCP listeners) it reports every virtual call as a call on an invalid object.
  target_compile_options(hil_warnings INTERFACE -fsanitize=address,${HIL_SANITIZE_UB} -fno-sanitize=vptr
    -fno-omit-frame-pointer -fno-sanitize-recover=all -Wno-stringop-overflow)
  target_link_options(hil_warnings INTERFACE -fsanitize=address,${HIL_SANITIZE_UB})
endif()
if(HIL_SANITIZE_THREAD)
  # -Wno-tsan: Asio's handler invocation (asio/detail/std_fenced_block.hpp) uses
  # std::atomic_thread_fence, which TSan does not model (g++ warns); the synchronisation TSan does
  # see, the scheduler's and reactor's mutexes, is what orders a handler after its initiation.
  target_compile_options(hil_warnings INTERFACE -fsanitize=thread -fno-omit-frame-pointer -Wno-tsan)
  target_link_options(hil_warnings INTERFACE -fsanitize=thread)
endif()
add_library(hil::warnings ALIAS hil_warnings)

function(hil_add_subfolders parent)
  file(GLOB children LIST_DIRECTORIES true RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/${parent}
       ${CMAKE_CURRENT_SOURCE_DIR}/${parent}/*)
  list(SORT children)
  foreach(child IN LISTS children)
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${parent}/${child}/CMakeLists.txt AND NOT child STREQUAL "cli")
      add_subdirectory(${parent}/${child})
    endif()
  endforeach()
endfunction()

# hil_add_library(NAME core SOURCES ... [LIBS ...] [INTERNAL])  -> target hil_core, alias hil::core,
# public headers in ./include. Unless INTERNAL, `cmake --install` installs the static library and
# its headers and exports it as hil::core in the hilbridge CMake package (cmake/HilInstall.cmake).
function(hil_add_library)
  cmake_parse_arguments(A "INTERNAL" "NAME" "SOURCES;LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(hil_${A_NAME} ${A_SOURCES})
  add_library(hil::${A_NAME} ALIAS hil_${A_NAME})
  target_include_directories(hil_${A_NAME} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                                  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  # Warnings are a build-tree matter: the exported targets do not carry them.
  target_link_libraries(hil_${A_NAME} PUBLIC ${A_LIBS} PRIVATE $<BUILD_INTERFACE:hil::warnings> ${A_PRIVATE_LIBS})
  target_compile_features(hil_${A_NAME} PUBLIC cxx_std_23)
  if(NOT A_INTERNAL)
    set_target_properties(hil_${A_NAME} PROPERTIES EXPORT_NAME ${A_NAME})
    install(TARGETS hil_${A_NAME} EXPORT hilbridgeTargets
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
    if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include)
      install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
              COMPONENT dev)
    endif()
    set_property(GLOBAL APPEND PROPERTY HIL_INSTALLED_LIBRARIES hil_${A_NAME})
  endif()
endfunction()

# hil_add_test(NAME motion_trajectory SOURCES ... LIBS ... [LABELS kernel])
# One googletest binary per concern; ctest sees every TEST() separately.
function(hil_add_test)
  cmake_parse_arguments(A "" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(test_${A_NAME} ${A_SOURCES})
  target_link_libraries(test_${A_NAME} PRIVATE ${A_LIBS} GTest::gtest GTest::gmock GTest::gtest_main hil::warnings)
  # Never a unity build (the preset ci builds the libraries and the CLI as unity batches): a test
  # binary is mostly one file, and googletest fixtures in anonymous namespaces are only legal in
  # the main file (-Wsubobject-linkage).
  set_target_properties(test_${A_NAME} PROPERTIES UNITY_BUILD OFF)
  if(NOT A_TIMEOUT)
    set(A_TIMEOUT 120)
  endif()
  set(labels ${A_LABELS})
  if(NOT labels)
    set(labels unit)
  endif()
  gtest_discover_tests(test_${A_NAME} DISCOVERY_TIMEOUT 60
    PROPERTIES LABELS "${labels}" TIMEOUT ${A_TIMEOUT}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()
include(GoogleTest OPTIONAL)

# hil_add_fuzzer(NAME sdo_server SOURCES fuzz_sdo.cpp LIBS hil::canopen [CORPUS dir])
# The source defines LLVMFuzzerTestOneInput. With HIL_FUZZ=ON (clang) it links libFuzzer;
# otherwise it links a replay driver and ctest runs it over its corpus plus a fixed-seed
# stream of mutated inputs, so every parser's fuzz target runs in every CI build.
function(hil_add_fuzzer)
  cmake_parse_arguments(A "" "NAME;CORPUS" "SOURCES;LIBS" ${ARGN})
  add_executable(fuzz_${A_NAME} ${A_SOURCES})
  target_link_libraries(fuzz_${A_NAME} PRIVATE ${A_LIBS} hil::warnings)
  set(corpus ${A_CORPUS})
  if(NOT corpus)
    set(corpus ${CMAKE_CURRENT_SOURCE_DIR}/corpus/${A_NAME})
  endif()
  set_property(GLOBAL APPEND PROPERTY HIL_FUZZ_TARGETS "${A_NAME}=${corpus}")
  if(HIL_FUZZ)
    target_compile_options(fuzz_${A_NAME} PRIVATE -fsanitize=fuzzer,address,undefined)
    target_link_options(fuzz_${A_NAME} PRIVATE -fsanitize=fuzzer,address,undefined)
  else()
    target_link_libraries(fuzz_${A_NAME} PRIVATE hil_fuzz_replay)
    add_test(NAME fuzz.${A_NAME} COMMAND fuzz_${A_NAME} --iterations=${HIL_FUZZ_REPLAY_ITERATIONS} ${corpus})
    set_tests_properties(fuzz.${A_NAME} PROPERTIES LABELS fuzz TIMEOUT 120)
  endif()
endfunction()

# hil_add_bench(NAME motion SOURCES ... LIBS ...) -> bench_motion (Google Benchmark; run with
# --benchmark_format=json). Not a ctest: speed goals live in benchmarks, not in tests.
function(hil_add_bench)
  cmake_parse_arguments(A "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(bench_${A_NAME} ${A_SOURCES})
  target_link_libraries(bench_${A_NAME} PRIVATE ${A_LIBS} benchmark::benchmark benchmark::benchmark_main hil::warnings)
endfunction()

# hil_add_cli_module(NAME can SOURCES ... LIBS ...)
# The source defines `void hil::cli::register_<NAME>(hil::cli::Context&)`; the generated
# registry in bridge/cli calls every module in name order.
function(hil_add_cli_module)
  cmake_parse_arguments(A "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_library(hil_cli_${A_NAME} OBJECT ${A_SOURCES})
  target_link_libraries(hil_cli_${A_NAME} PUBLIC hil::cli_base ${A_LIBS} PRIVATE hil::warnings)
  set_property(GLOBAL APPEND PROPERTY HIL_CLI_MODULES ${A_NAME})
endfunction()
