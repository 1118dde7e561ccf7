#include "io/SiteVtk.hpp"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

#include <cmath>

namespace fw::io {

void add_site_field_data(vtkFieldData& data, const SiteSettings& site) {
  vtkNew<vtkDoubleArray> origin;
  origin->SetName("site_origin");
  origin->SetNumberOfComponents(3);
  origin->InsertNextTuple(site.origin.data());
  data.AddArray(origin);
  vtkNew<vtkIntArray> epsg;
  epsg->SetName("site_epsg");
  epsg->InsertNextValue(site.crs && site.crs->epsg ? *site.crs->epsg : 0);
  data.AddArray(epsg);
  if (!site.crs) return;
  vtkNew<vtkStringArray> crs;
  crs->SetName("site_crs");
  crs->InsertNextValue(site.crs->wkt);
  data.AddArray(crs);
}

std::optional<SiteSettings> read_site_field_data(vtkFieldData& data) {
  vtkDataArray* origin = data.GetArray("site_origin");
  if (!origin || origin->GetNumberOfComponents() != 3 || origin->GetNumberOfTuples() < 1) return std::nullopt;
  SiteSettings site;
  for (int axis = 0; axis < 3; ++axis) {
    site.origin[std::size_t(axis)] = origin->GetComponent(0, axis);
    if (!std::isfinite(site.origin[std::size_t(axis)])) return std::nullopt;
  }
  auto* crs = vtkStringArray::SafeDownCast(data.GetAbstractArray("site_crs"));
  if (crs && crs->GetNumberOfValues() >= 1 && !crs->GetValue(0).empty()) {
    CoordinateSystem& system = site.crs.emplace();
    system.wkt = crs->GetValue(0);
    if (vtkDataArray* epsg = data.GetArray("site_epsg"); epsg && epsg->GetNumberOfTuples() >= 1) {
      const double code = epsg->GetComponent(0, 0);
      if (code > 0) system.epsg = int(code);
    }
  }
  return site;
}

}  // namespace fw::io
