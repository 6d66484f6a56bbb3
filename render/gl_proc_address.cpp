// VTK 9.1 on Debian is built for GLX: its GLEW loader asks glXGetProcAddressARB for every
// GL entry point. Executables that render off-screen export this symbol (CMake
// ENABLE_EXPORTS, OSMesa linked before VTK) so that the lookup lands in OSMesa instead of
// an X11 libGL, and no X server is needed. Compiled into each rendering executable (an
// object library), never into a shared library.
#include <GL/osmesa.h>

extern "C" __attribute__((visibility("default"))) void (*glXGetProcAddressARB(const unsigned char* name))() {
  return reinterpret_cast<void (*)()>(OSMesaGetProcAddress(reinterpret_cast<const char*>(name)));
}
