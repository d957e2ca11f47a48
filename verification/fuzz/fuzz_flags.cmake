# Included by the top-level CMakeLists.txt when HOFEM_FUZZ is on, before any target
# exists, so that core and everything else carry the same instrumentation:
# coverage for libFuzzer (fuzzer-no-link: the engine itself is linked only into the
# fuzz targets), AddressSanitizer, and UndefinedBehaviorSanitizer made fatal so a
# UB report is a crash libFuzzer records.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT CMAKE_C_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR
    "hofem: HOFEM_FUZZ needs clang (libFuzzer is part of clang); this build uses "
    "${CMAKE_C_COMPILER_ID} / ${CMAKE_CXX_COMPILER_ID}. Configure a fresh build directory with "
    "CC=clang CXX=clang++ (Debian packages 'clang' and 'libclang-rt-14-dev'), or run scripts/fuzz.")
endif()
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
add_link_options(-fsanitize=address,undefined)
# The project's GCC-only -Wno-maybe-uninitialized would warn once per file.
add_compile_options(-Wno-unknown-warning-option)
