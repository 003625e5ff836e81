// The front ends' GL paths: the gpu module's functions installed into the library's operations
// (operations/gpu_backend.h). Compiled into the CLI and the Python extension; without the module
// (SKYLIGHT_GPU=OFF) it installs nothing and the GL paths say so.
#pragma once

namespace skylight::frontend {

void install_gpu_backend();

}  // namespace skylight::frontend
