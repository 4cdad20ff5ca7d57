# Installs the ThinTissue build into a scratch prefix, then configures,
# builds and runs the consumer project against it.
set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${prefix}")

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${what} failed (${code}):\n${out}")
  endif()
  message("${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

run_step("install" "${CMAKE_COMMAND}" --install "${THINTISSUE_BUILD_DIR}" --prefix "${prefix}")
set(launcher)
find_program(ccache ccache)
if(ccache)
  set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${ccache}")
endif()
set(sanitized)
if(CONSUMER_SANITIZER_FLAGS)
  set(sanitized "-DCMAKE_CXX_FLAGS=${CONSUMER_SANITIZER_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_SANITIZER_FLAGS}")
endif()
run_step("configure" "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${consumer_build}"
  -G "${GENERATOR}" "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release ${launcher}
  ${sanitized})
run_step("build" "${CMAKE_COMMAND}" --build "${consumer_build}")
run_step("run" "${consumer_build}/consumer")
message("${step_output}")
if(NOT step_output MATCHES "package works")
  message(FATAL_ERROR "consumer did not confirm the package")
endif()

# The installed Python package imports and works from the prefix.
if(PYTHON_EXECUTABLE AND PYTHON_DESTINATION)
  set(preload)
  if(PYTHON_PRELOAD)
    set(preload "LD_PRELOAD=${PYTHON_PRELOAD}" "ASAN_OPTIONS=detect_leaks=0")
  endif()
  run_step("python" "${CMAKE_COMMAND}" -E env "PYTHONPATH=${prefix}/${PYTHON_DESTINATION}" ${preload}
    "${PYTHON_EXECUTABLE}" -c
    # No semicolons: they would split the CMake argument list.
    "import thintissue\ns = thintissue.vtkThinSlabSource()\ns.Update()\nprint('python package works', s.GetOutput().GetNumberOfPolys())")
  message("${step_output}")
  if(NOT step_output MATCHES "python package works")
    message(FATAL_ERROR "installed Python package did not work")
  endif()
endif()
