// stb_image and stb_image_write compiled into the fuzz build (instead of the system libstb), so
// that the HDR reader behind io::read_image runs instrumented: coverage feedback and sanitizer
// checks inside it, not only in our wrapper.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
