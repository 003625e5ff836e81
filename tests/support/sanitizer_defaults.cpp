// Default runtime options of the ASan + UBSan build (SKYLIGHT_SANITIZE=ON), linked into every
// executable that can open the GL module (skylight_tests, the CLI, skylight_bench when built).
// ASAN_OPTIONS in the environment is parsed after these and can override them.
//
// intercept_tls_get_addr=0: GCC 12's sanitizer runtime (libsanitizer, as in GCC <= 13 and
// compiler-rt <= 16) intercepts __tls_get_addr and, when a dynamic TLS block starts 16 bytes past
// a 4096-byte boundary, takes the two words before it for a glibc 2.19 header holding the block's
// start and size (sanitizer_tls_get_addr.cpp, DTLS_on_tls_get_addr). glibc >= 2.25 has no such
// header: a block that lands there by chance gives LeakSanitizer a garbage range, and its
// exit-time scan crashes ("Tracer caught signal 11", "LeakSanitizer has encountered a fatal
// error") after the test has passed. Mesa's driver (loaded by the gpu/ tests and `render --gpu`)
// uses dynamic TLS (one block per GL process, malloc'd at the first frame, its address set by
// the allocations before it), so a GL test failed this way in one CI run after its checks had
// passed. A program that makes k 32-byte allocations before one GL frame crashed so in 4 of 123
// runs (k = 100..140, three times) with the interception, in none without it. Without it the
// blocks are still scanned: glibc allocates them with malloc and the thread's DTV points at them,
// so LeakSanitizer reaches them from the thread's static TLS like any other heap block, and leaks
// are still found (a 77-byte leak in the same GL process was reported).
extern "C" const char* __asan_default_options();
extern "C" const char* __asan_default_options() {
  return "intercept_tls_get_addr=0";
}
