# -DFFR_FUZZ=ON: the build of tools/fuzz's libFuzzer programs (tools/fuzz/README.md). Needs clang
# (Debian: clang, libclang-rt-14-dev) and a build folder of its own (tools/fuzz/run.sh uses
# build-fuzz/): every object is compiled with libFuzzer's coverage instrumentation and with
# AddressSanitizer and UndefinedBehaviorSanitizer, so that a memory error or undefined behaviour
# anywhere in the project's readers stops the fuzzer with the input that caused it.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "FFR_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
endif()
# Line tables only (enough for the sanitizers' reports) and no vptr check: both cost much of the
# compile time of the Eigen-heavy sources and little of what fuzzing finds.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined
                    -fno-omit-frame-pointer -gline-tables-only)
add_link_options(-fsanitize=address,undefined -fno-sanitize=vptr)
