// The OpenCL C sources of kernels/, embedded into the binary at build time.
// Setting FORESTWIND_KERNEL_DIR loads them from that folder instead, for kernel development.
#pragma once

#include <string>
#include <vector>

namespace fw::host {

/// Text of one file of kernels/ ("fluid_advect.cl", "shared_types.h", ...), with every
/// `#include "NAME"` line replaced by the named file (each file included once).
/// Throws std::runtime_error naming the file when it does not exist.
std::string kernel_source(const std::string& file_name);

/// Names of the embedded files.
std::vector<std::string> embedded_kernel_files();

}  // namespace fw::host
