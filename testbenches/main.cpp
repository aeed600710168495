// The test runner: Catch2's own main cannot run BENCHMARKs with the packaged Catch2,
// and SystemC testbenches will route their reports through here.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

int main(int argc, char* argv[]) { return Catch::Session().run(argc, argv); }
