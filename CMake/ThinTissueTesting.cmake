# One-line test registration for ThinTissue:
#   thintissue_add_gtest(NAME SOURCES a.cxx b.cxx LIBRARIES ThinTissue::Core)
#   thintissue_add_image_test(NAME SOURCE TestX.cxx LIBRARIES ... [THRESHOLD t])
#   thintissue_add_python_test(NAME SCRIPT test_x.py)
# Image tests compare against Testing/Data/Baseline/<NAME>.png; a missing or
# different image is written to <build>/Testing/Temporary/<NAME>.png.

set(THINTISSUE_BASELINE_DIR "${PROJECT_SOURCE_DIR}/Testing/Data/Baseline")
set(THINTISSUE_TEST_TEMPORARY_DIR "${PROJECT_BINARY_DIR}/Testing/Temporary")
file(MAKE_DIRECTORY "${THINTISSUE_TEST_TEMPORARY_DIR}")
include(GoogleTest)

# C++ tests get these as compile-time defaults (ctest's ENVIRONMENT lists do
# not survive gtest_discover_tests); the environment variables override them.
set(THINTISSUE_TEST_DEFINITIONS
  "THINTISSUE_TEST_SHARED_DATA_DEFAULT=\"${THINTISSUE_SHARED_DATA_DIR}\""
  "THINTISSUE_TEST_TEMPORARY_DEFAULT=\"${THINTISSUE_TEST_TEMPORARY_DIR}\"")

set(THINTISSUE_TEST_ENVIRONMENT
  "THINTISSUE_SHARED_DATA=${THINTISSUE_SHARED_DATA_DIR}"
  "THINTISSUE_TEST_TEMPORARY=${THINTISSUE_TEST_TEMPORARY_DIR}"
  "THINTISSUE_TEST_DATA=${PROJECT_SOURCE_DIR}/Testing/Data")

function(thintissue_add_gtest name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SOURCES;LIBRARIES")
  add_executable(${name} ${arg_SOURCES})
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES} GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE "${PROJECT_SOURCE_DIR}/Testing/Support")
  target_compile_definitions(${name} PRIVATE ${THINTISSUE_TEST_DEFINITIONS})
  gtest_discover_tests(${name}
    DISCOVERY_MODE PRE_TEST
    TEST_PREFIX "${name}."
    PROPERTIES LABELS "unit")
endfunction()

function(thintissue_add_image_test name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "SOURCE;THRESHOLD" "LIBRARIES")
  add_executable(${name} ${arg_SOURCE})
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES}
    VTK::TestingRendering VTK::RenderingOpenGL2 VTK::RenderingFreeType VTK::InteractionStyle)
  target_include_directories(${name} PRIVATE "${PROJECT_SOURCE_DIR}/Testing/Support")
  target_compile_definitions(${name} PRIVATE ${THINTISSUE_TEST_DEFINITIONS})
  vtk_module_autoinit(TARGETS ${name} MODULES
    VTK::RenderingOpenGL2 VTK::RenderingFreeType VTK::InteractionStyle)
  set(threshold_args)
  if(arg_THRESHOLD)
    set(threshold_args --threshold ${arg_THRESHOLD})
  endif()
  add_test(NAME ${name}
    COMMAND ${name} -V "${THINTISSUE_BASELINE_DIR}/${name}.png"
      -T "${THINTISSUE_TEST_TEMPORARY_DIR}" ${threshold_args})
  # 77: optional data missing (reported as skipped, not passed).
  set_tests_properties(${name} PROPERTIES
    ENVIRONMENT "${THINTISSUE_TEST_ENVIRONMENT}" LABELS "rendering" SKIP_RETURN_CODE 77)
endfunction()

function(thintissue_add_python_test name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "SCRIPT" "")
  add_test(NAME ${name} COMMAND "${Python3_EXECUTABLE}" "${CMAKE_CURRENT_SOURCE_DIR}/${arg_SCRIPT}")
  set_tests_properties(${name} PROPERTIES
    ENVIRONMENT "${THINTISSUE_TEST_ENVIRONMENT};PYTHONPATH=${THINTISSUE_PYTHON_PACKAGE_DIR}"
    LABELS "python" SKIP_RETURN_CODE 77)
endfunction()
