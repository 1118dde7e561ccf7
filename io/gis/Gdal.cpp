#include "io/gis/Gdal.hpp"

#include <cpl_error.h>
#include <gdal_priv.h>

#include <mutex>

namespace fw::io::gdal {

void CloseDataset::operator()(GDALDataset* dataset) const {
  GDALClose(GDALDataset::ToHandle(dataset));
}

void register_drivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

QuietErrors::QuietErrors() {
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLErrorReset();
}

QuietErrors::~QuietErrors() {
  CPLPopErrorHandler();
}

std::string QuietErrors::last_message() {
  const char* message = CPLGetLastErrorMsg();
  return message && *message ? message : "no reason given";
}

}  // namespace fw::io::gdal
