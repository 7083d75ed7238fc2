// The one source of anyphys_test_pch (tests/CMakeLists.txt), the target that owns the header the
// test programs share precompiled. It defines nothing: a precompiled header is refused by a
// program that lacks one of its owner's definitions.
