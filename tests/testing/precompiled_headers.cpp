// The one source of flat2d_test_pch (tests/CMakeLists.txt): a target needs a source to
// compile its precompiled header, which the test executables then reuse.
