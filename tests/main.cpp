// The Catch2 main of the mfree test suite; every test file under tests/ mirrors a source path.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
