// The test runner: Catch2's own main cannot run BENCHMARKs with the packaged Catch2,
// and SystemC testbenches will route their reports through here.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>

// libsystemc's own main() would call sc_main; this runner starts simulations from
// the test cases instead, so sc_main only satisfies the linker.
extern "C" int sc_main(int, char**) { return 1; }

int main(int argc, char* argv[]) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  return Catch::Session().run(argc, argv);
}
