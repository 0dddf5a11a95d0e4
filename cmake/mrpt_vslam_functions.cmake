# Helpers shared by every library, app, test and benchmark of the project.

set(MRPT_VSLAM_CMAKE_DIR ${CMAKE_CURRENT_LIST_DIR})

# Compile options applied to every target of ours (never globally).
function(mrpt_vslam_set_target_options target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wshadow=local)
  endif()
  if(MRPT_VSLAM_FUZZ)  # coverage for libFuzzer in every target of ours
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
  if(MRPT_VSLAM_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined
                                             # MRPT 2.5 opengl classes with Eigen members
                                             # sit in under-aligned virtual bases
                                             -fno-sanitize=alignment
                                             # GCC 12 sees uninitialized members inside
                                             # libstdc++'s <regex> under the instrumentation
                                             # (false positives); the normal build keeps it
                                             $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# mrpt_vslam_add_library(<name> [STATIC] SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Builds the shared (or, with STATIC, static) library mrpt_vslam_<name> (alias
# mrpt_vslam::<name>) from libs/<name>, with headers under libs/<name>/include/mrpt_vslam/<name>/.
function(mrpt_vslam_add_library name)
  cmake_parse_arguments(A "STATIC" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target mrpt_vslam_${name})
  if(A_STATIC)
    add_library(${target} STATIC ${A_SOURCES})
  else()
    add_library(${target} SHARED ${A_SOURCES})
  endif()
  add_library(mrpt_vslam::${name} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${A_PUBLIC_DEPS} PRIVATE ${A_PRIVATE_DEPS})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} VERSION ${PROJECT_VERSION}
                                             SOVERSION ${PROJECT_VERSION_MAJOR})
  mrpt_vslam_set_target_options(${target})
  install(TARGETS ${target} EXPORT mrpt_vslamTargets
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# mrpt_vslam_add_app(<name> SOURCES ... DEPS ...): an installed executable in build/bin.
function(mrpt_vslam_add_app name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_DEPS})
  mrpt_vslam_set_target_options(${name})
  install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# mrpt_vslam_add_test(<name> SOURCES ... DEPS ... [LABELS ...]): a GoogleTest program run by ctest.
# Tests find the repository's data through MRPT_VSLAM_SOURCE_DIR and the built apps through
# MRPT_VSLAM_BIN_DIR.
function(mrpt_vslam_add_test name)
  if(NOT MRPT_VSLAM_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(A "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_DEPS} GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  target_compile_definitions(${name} PRIVATE
    MRPT_VSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    MRPT_VSLAM_BIN_DIR="${CMAKE_RUNTIME_OUTPUT_DIRECTORY}")
  mrpt_vslam_set_target_options(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  add_test(NAME ${name} COMMAND ${name} WORKING_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  if(A_LABELS)
    set_tests_properties(${name} PROPERTIES LABELS "${A_LABELS}")
  endif()
endfunction()

# mrpt_vslam_add_benchmark(<name> SOURCES ... DEPS ...): a Google Benchmark program (not run by ctest).
function(mrpt_vslam_add_benchmark name)
  if(NOT MRPT_VSLAM_BUILD_BENCHMARKS)
    return()
  endif()
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${A_SOURCES} ${PROJECT_SOURCE_DIR}/tests/bench/RetainFreedMemory.cpp)
  target_link_libraries(${name} PRIVATE ${A_DEPS} mrpt_vslam::core benchmark::benchmark
                        benchmark::benchmark_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  target_compile_definitions(${name} PRIVATE MRPT_VSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  mrpt_vslam_set_target_options(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
endfunction()

# Installs the CMake package so outside programs can find_package(mrpt_vslam) and link
# mrpt_vslam::<name>.
function(mrpt_vslam_install_package)
  include(CMakePackageConfigHelpers)
  set(cfgdir ${CMAKE_INSTALL_LIBDIR}/cmake/mrpt_vslam)
  install(EXPORT mrpt_vslamTargets NAMESPACE mrpt_vslam:: DESTINATION ${cfgdir})
  configure_package_config_file(${MRPT_VSLAM_CMAKE_DIR}/mrpt_vslamConfig.cmake.in
    ${CMAKE_BINARY_DIR}/mrpt_vslamConfig.cmake INSTALL_DESTINATION ${cfgdir})
  write_basic_package_version_file(${CMAKE_BINARY_DIR}/mrpt_vslamConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
  install(FILES ${CMAKE_BINARY_DIR}/mrpt_vslamConfig.cmake
                ${CMAKE_BINARY_DIR}/mrpt_vslamConfigVersion.cmake DESTINATION ${cfgdir})
endfunction()
