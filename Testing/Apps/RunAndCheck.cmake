# cmake -DCOMMAND="exe;args" -DEXPECT_EXIT=N [-DEXPECT_OUTPUT=regex]
#       [-DEXPECT_FILES="f1;f2"] [-DEXPECT_PLAIN_LINES=ON] -P RunAndCheck.cmake
# Runs COMMAND; fails unless the exit code, the combined output and the
# produced files are as expected. EXPECT_PLAIN_LINES: the output (to a
# pipe, not a terminal) holds no carriage return, as a log file needs.
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
if(EXPECT_PLAIN_LINES)
  string(ASCII 13 carriage_return)
  string(FIND "${output}" "${carriage_return}" position)
  if(NOT position EQUAL -1)
    message(FATAL_ERROR "output holds a carriage return (at ${position}): not plain lines")
  endif()
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
