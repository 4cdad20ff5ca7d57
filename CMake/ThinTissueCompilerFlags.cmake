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
