# FFR_SANITIZE: build everything with AddressSanitizer and UndefinedBehaviorSanitizer.
# scripts/test.sh configures a second build tree with it (build-asan/, tests only) and runs the
# suite there; the run options (halt on the first report) are set in that script.
#
# Every target of the tree is instrumented, so a report's stack names our lines; the system
# libraries (OpenBLAS, CHOLMOD, HDF5, gmsh) are not, but their reads of our buffers and the
# buffers they hand back are checked through the intercepted allocator. -O1 keeps the suite fast
# enough to run whole; a Debug build keeps asserts (Eigen's index checks among them) on.
option(FFR_SANITIZE "Build with -fsanitize=address,undefined (the test command's second build)" OFF)
if(FFR_SANITIZE)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    message(FATAL_ERROR "FFR_SANITIZE needs GCC or Clang (found ${CMAKE_CXX_COMPILER_ID})")
  endif()
  # UBSan's null and alignment checks are left out: they guard every member access and took the
  # compile time of an Eigen-heavy source from 15.9 to 26.7 CPU-s (runtime/src/bodies/
  # body_inertia.cpp; plain -O2 takes 10.4), the largest part of the test command's time, while
  # a null dereference still stops the run (ASan reports the SEGV with its stack) and x86-64
  # loads at any alignment (aligned SIMD loads that miss fault all the same).
  set(FFR_SANITIZE_FLAGS -fsanitize=address,undefined -fno-sanitize=null,alignment
      -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options(${FFR_SANITIZE_FLAGS} $<$<CONFIG:Debug>:-O1>)
  add_link_options(-fsanitize=address,undefined)
endif()
