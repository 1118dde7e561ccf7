// Choosing an OpenCL device.
//
//   auto devices = fw::host::list_devices();                 // every platform's devices
//   cl::Device d = fw::host::select_device("pocl");          // filter: substring of platform or device name
//   cl::Device d = fw::host::select_device(fw::host::device_filter_from_env(""));
//
// With an empty filter the first GPU wins, else the first CPU device, else the first device of any type.
// Matching is case-insensitive. NoDeviceError is thrown when no platform exists or nothing matches.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/runtime/opencl.hpp"

namespace fw::host {

struct DeviceInfo {
  int platform_index = 0;
  int device_index = 0;  // within its platform
  std::string platform_name;
  std::string platform_version;
  std::string device_name;
  std::string device_version;
  std::string type;  // "GPU", "CPU", "accelerator" or "other"
  unsigned compute_units = 0;
  std::uint64_t global_memory_bytes = 0;
  std::uint64_t max_allocation_bytes = 0;
  std::uint64_t local_memory_bytes = 0;
  unsigned max_clock_mhz = 0;
  cl::Device device;
};

/// Every device of every platform. Throws NoDeviceError if there is no OpenCL platform at all.
std::vector<DeviceInfo> list_devices();

/// The device chosen by `filter` (see the header comment).
DeviceInfo select_device(const std::string& filter);
/// The device of a machine's rank `node_rank` (docs/parallel.md): of the devices the filter matches (else the
/// GPUs, else the CPUs, else all), the node_rank-th, counted round; node_rank 0 is select_device(filter).
/// Ranks beyond the count share devices; ranks on a CPU share it (see share_cpu_cores).
DeviceInfo select_device(const std::string& filter, int node_rank);

/// Gives each of `node_ranks` ranks on this machine its share of the cores under PoCL: sets
/// POCL_MAX_PTHREAD_COUNT to max(1, cores / node_ranks) unless the environment already sets it, and returns
/// the share in force (0: one rank, nothing set). It must run before the first OpenCL call of the process.
int share_cpu_cores(int node_ranks);

/// `command_line_filter` if not empty, else the environment variable FORESTWIND_DEVICE, else "".
std::string device_filter_from_env(const std::string& command_line_filter);

/// The message for "no platform": it names the Debian package that provides one.
std::string no_platform_message();

}  // namespace fw::host
