# AddressSanitizer + UndefinedBehaviorSanitizer for the whole build when FLAT2D_SANITIZE is on.
# Debug information comes from the build type (scripts/build asan asks for line tables,
# -g1): a -g here would come later on the command line and override it, which made the
# objects four times larger and the build about 40 % slower for no better report.
if(FLAT2D_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

# libFuzzer instrumentation for the library code used by fuzz targets.
if(FLAT2D_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "FLAT2D_FUZZ needs clang (CXX=clang++)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -g)
  add_link_options(-fsanitize=address,undefined)
endif()
