// The translation unit that makes the tests' precompiled header
// (cmake/DriveidTest.cmake: driveid_test_pch); it defines nothing.
