// The source of lcprelax_test_pch (tests/CMakeLists.txt): the executable exists to build the
// tests' precompiled header once, with the tests' flags; it holds no test and is not run.
