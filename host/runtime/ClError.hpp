// OpenCL failures as exceptions that say what failed: the kernel or call, the error name, and for a
// failed build the .cl file and the compiler's log.
#pragma once

#include <stdexcept>
#include <string>

namespace fw::host {

/// Symbolic name of an OpenCL status code, e.g. "CL_OUT_OF_RESOURCES".
std::string cl_status_name(int status);

/// A failed OpenCL call. `what` reads "<where>: <CL_STATUS_NAME> (<code>)".
class ClError : public std::runtime_error {
 public:
  ClError(const std::string& where, int status);
  int status() const { return status_; }

 private:
  int status_;
};

/// A kernel file that did not compile. `what` names the file and carries the build log.
class KernelBuildError : public std::runtime_error {
 public:
  KernelBuildError(const std::string& file, const std::string& log);
  const std::string& file() const { return file_; }
  const std::string& log() const { return log_; }

 private:
  std::string file_, log_;
};

/// No OpenCL platform, or no device that matches the filter. The command line maps it to exit code 3.
class NoDeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace fw::host
