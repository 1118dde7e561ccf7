// What the io/gis readers and writers share about GDAL: its drivers registered once, and its error messages
// kept off stderr and read back for the exceptions they throw.
//
//   fw::io::gdal::register_drivers();
//   const fw::io::gdal::QuietErrors quiet;       // while it lives, GDAL prints nothing
//   if (!dataset) throw Error(fw::io::gdal::QuietErrors::last_message());
#pragma once

#include <memory>
#include <string>

class GDALDataset;

namespace fw::io::gdal {

/// Closes a dataset (GDALClose: a written one is flushed to its file then).
struct CloseDataset {
  void operator()(GDALDataset* dataset) const;
};
using Dataset = std::unique_ptr<GDALDataset, CloseDataset>;

/// GDALAllRegister, once per process.
void register_drivers();

class QuietErrors {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  /// GDAL's last error message since this was made, or "no reason given".
  static std::string last_message();
};

}  // namespace fw::io::gdal
