# Build time on a small machine (CI has two cores; docs/benchmarks.md, "Build and CI time").
#
# Linking: lld when the compiler can use it; GNU ld is the slowest part of linking the
# 127 test executables and the tools.
include(CheckLinkerFlag)
check_linker_flag(CXX "-fuse-ld=lld" FLAT2D_HAVE_LLD)
if(FLAT2D_HAVE_LLD)
  add_link_options(-fuse-ld=lld)
endif()

# Unity builds (-DCMAKE_UNITY_BUILD=ON, as scripts/build configures release and asan)
# compile a target's sources in batches, so the Eigen and gtest templates they share are
# instantiated and optimized once per batch rather than once per file. File-local names
# therefore must not repeat within a target. GCC reads a batched .cpp as an included
# file and then warns that a class with a member of an anonymous-namespace type has
# internal linkage (-Wsubobject-linkage), which is true of every such class in a .cpp.
# Clang has no such warning.
if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  add_compile_options(-Wno-subobject-linkage)
endif()
