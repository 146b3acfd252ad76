include(GoogleTest)

# Warnings for the project's own targets (not for idlc's generated C).
function(mpgc_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local -Wno-missing-field-initializers)
endfunction()

# A benchmark no test runs (./mpgc bench NAME): left out of the sanitizer build's default target,
# where nothing runs it and its compile is minutes of CI (cmake --build build-asan --target NAME
# builds it there).
function(mpgc_benchmark_defaults target)
  mpgc_target_defaults(${target})
  if(MPGC_SANITIZE)
    set_target_properties(${target} PROPERTIES EXCLUDE_FROM_ALL ON)
  endif()
endfunction()

# Adds every immediate subfolder of `dir` that has a CMakeLists.txt, so a new component or test
# folder needs no edit elsewhere.
function(mpgc_add_subdirectories dir)
  file(GLOB children RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/${dir} ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*)
  list(SORT children)
  foreach(child ${children})
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/${child}/CMakeLists.txt)
      add_subdirectory(${dir}/${child})
    endif()
  endforeach()
endfunction()

# mpgc_add_gtest(NAME name SOURCES ... LIBS ... LABELS unit|integration|scenario <component> [TIMEOUT s]
#                [SERIAL] [SERIAL_TESTS Suite.Name ...])
# SERIAL: ctest runs its tests alone (RUN_SERIAL), for closed loops at a real-time factor or with
# wall-clock windows whose outcome a second test competing for the 2 cores would change;
# SERIAL_TESTS: only these of its tests (a lockstep loop beside them needs no such care).
# Every test runs with the loopback Cyclone configuration and finds the shared data through
# MPGC_SHARED_DATA and the project's executables through MPGC_BIN_DIR.
function(mpgc_add_gtest)
  cmake_parse_arguments(T "SERIAL" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS;SERIAL_TESTS" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} mpgc_testing GTest::gtest GTest::gtest_main)
  mpgc_target_defaults(${T_NAME})
  gtest_discover_tests(${T_NAME} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60)
  # gtest_discover_tests (CMake 3.25) flattens list-valued PROPERTIES, so the labels and the
  # environment are set by a second include file that ctest reads after the discovered tests.
  set(env
    "CYCLONEDDS_URI=file://${PROJECT_SOURCE_DIR}/deploy/cyclonedds/loopback.xml"
    "MPGC_SHARED_DATA=${PROJECT_SOURCE_DIR}/../shared/data"
    "MPGC_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
    "MPGC_BIN_DIR=${CMAKE_BINARY_DIR}/bin"
    "ASAN_OPTIONS=detect_leaks=1"
    "UBSAN_OPTIONS=print_stacktrace=1")
  set(serial "")
  if(T_SERIAL)
    set(serial " RUN_SERIAL TRUE")
  endif()
  set(props_file ${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}_properties.cmake)
  file(WRITE ${props_file}
    "if(${T_NAME}_TESTS)\n"
    "  set_tests_properties(\${${T_NAME}_TESTS} PROPERTIES LABELS \"${T_LABELS}\" TIMEOUT ${T_TIMEOUT}${serial}\n"
    "    ENVIRONMENT \"${env}\")\n"
    "  foreach(t ${T_SERIAL_TESTS})\n"
    "    list(FIND ${T_NAME}_TESTS \${t} at)\n"  # ctest runs this without policy CMP0057 (IN_LIST)
    "    if(at GREATER -1)\n"
    "      set_tests_properties(\${t} PROPERTIES RUN_SERIAL TRUE)\n"
    "    else()\n"
    "      message(FATAL_ERROR \"${T_NAME}: SERIAL_TESTS names \${t}, not one of its tests\")\n"
    "    endif()\n"
    "  endforeach()\n"
    "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${props_file})
endfunction()
