# AddressSanitizer + UndefinedBehaviorSanitizer for the whole build when FLAT2D_SANITIZE is on.
# Debug information comes from the build type (scripts/build asan asks for line tables,
# -g1): a -g here would come later on the command line and override it, which made the
# objects four times larger and the build about 40 % slower for no better report.
if(FLAT2D_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
  # Eigen marks its small kernels (coefficient evaluators, fixed-size products) plain
  # inline. The sanitizers' instrumentation makes them large enough that the inliner leaves
  # many out of line, and a 6x6 product then costs a call per coefficient. Forcing them
  # inline keeps every check (instrumentation comes after inlining); `flat2d-eval loops`
  # runs 5.3 times as fast (docs/benchmarks.md, "Build and CI time").
  add_compile_definitions(EIGEN_STRONG_INLINE=EIGEN_ALWAYS_INLINE)
endif()

# libFuzzer instrumentation for the library code used by fuzz targets. Debug information
# comes from the build type, as above (scripts/build fuzz asks for line tables: a crash's
# stack keeps file and line).
if(FLAT2D_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "FLAT2D_FUZZ needs clang (CXX=clang++)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
