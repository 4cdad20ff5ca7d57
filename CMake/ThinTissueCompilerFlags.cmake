# Warnings, sanitizers and compiler cache for every ThinTissue target.
find_program(THINTISSUE_CCACHE ccache)
if(THINTISSUE_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  set(CMAKE_C_COMPILER_LAUNCHER "${THINTISSUE_CCACHE}")
  set(CMAKE_CXX_COMPILER_LAUNCHER "${THINTISSUE_CCACHE}")
endif()

if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  add_compile_options("$<$<COMPILE_LANGUAGE:CXX>:-Wall;-Wextra;-Wno-deprecated-copy>")
endif()

if(THINTISSUE_ENABLE_SANITIZERS)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# Data races between the servo, physics and GUI threads (DESIGN.md: real-time
# loop). ThreadSanitizer cannot be combined with AddressSanitizer.
if(THINTISSUE_ENABLE_THREAD_SANITIZER)
  if(THINTISSUE_ENABLE_SANITIZERS)
    message(FATAL_ERROR "THINTISSUE_ENABLE_THREAD_SANITIZER and THINTISSUE_ENABLE_SANITIZERS "
      "cannot be on together (ThreadSanitizer excludes AddressSanitizer): use two build directories")
  endif()
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()

# Instruction set. The solver's products and factor solves, the element
# assembly and the contact kernels run Eigen's vector code: with AVX2 and
# FMA (x86-64-v3) the punch replay ran 12-15 % faster than on the generic
# x86-64 (SSE2) code (twenty-eighth session). Taken when the building
# machine runs it; THINTISSUE_CPU_FLAGS overrides (empty: a portable build,
# or e.g. -march=native). -ffp-contract=off: GCC would otherwise contract
# every a * b + c (ours and CGAL's) into an FMA, which rounds differently
# and changed exact-geodesic and segmentation results (8 tests failed);
# Eigen's vector kernels call FMA explicitly and keep it.
if(NOT DEFINED THINTISSUE_CPU_FLAGS)
  set(thintissue_cpu_flags "")
  if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64" AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND
     NOT CMAKE_CROSSCOMPILING)
    include(CheckCXXSourceRuns)
    set(CMAKE_REQUIRED_FLAGS "-march=x86-64-v3")
    check_cxx_source_runs(
      "int main() { __builtin_cpu_init(); return __builtin_cpu_supports(\"x86-64-v3\") ? 0 : 1; }"
      THINTISSUE_CPU_RUNS_X86_64_V3)
    unset(CMAKE_REQUIRED_FLAGS)
    if(THINTISSUE_CPU_RUNS_X86_64_V3)
      set(thintissue_cpu_flags "-march=x86-64-v3 -ffp-contract=off")
    endif()
  endif()
  set(THINTISSUE_CPU_FLAGS "${thintissue_cpu_flags}" CACHE STRING
    "Instruction-set flags of every ThinTissue target (default: -march=x86-64-v3 when the building machine runs AVX2 and FMA; empty for a portable build)")
endif()
if(THINTISSUE_CPU_FLAGS)
  separate_arguments(thintissue_cpu_flag_list UNIX_COMMAND "${THINTISSUE_CPU_FLAGS}")
  add_compile_options(${thintissue_cpu_flag_list})
endif()
message(STATUS "ThinTissue instruction-set flags: '${THINTISSUE_CPU_FLAGS}'")
