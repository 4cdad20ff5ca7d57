# cmake -DCOMMAND="exe;args" -DEXPECT_EXIT=N [-DEXPECT_OUTPUT=regex]
#       [-DEXPECT_FILES="f1;f2"] -P RunAndCheck.cmake
# Runs COMMAND; fails unless the exit code, the combined output and the
# produced files are as expected.
foreach(file IN LISTS EXPECT_FILES)
  file(REMOVE "${file}")
endforeach()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE exit_code
  OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(NOT "${exit_code}" STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "exit code ${exit_code}, expected ${EXPECT_EXIT}")
endif()
if(DEFINED EXPECT_OUTPUT AND NOT output MATCHES "${EXPECT_OUTPUT}")
  message(FATAL_ERROR "output does not match '${EXPECT_OUTPUT}'")
endif()
foreach(file IN LISTS EXPECT_FILES)
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "expected file not written: ${file}")
  endif()
  file(SIZE "${file}" size)
  if(size EQUAL 0)
    message(FATAL_ERROR "file is empty: ${file}")
  endif()
endforeach()
