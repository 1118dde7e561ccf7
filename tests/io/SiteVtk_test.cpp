// The site in the VTK frames' field data (io/SiteVtk.hpp): written by the wind and trees writers, read back
// as ParaView's reader reads it.
#include "io/SiteVtk.hpp"

#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "io/TreesVtk.hpp"
#include "io/WindVtk.hpp"
#include "tests/support/TempDir.hpp"

namespace {

fw::io::SiteSettings utm_site() {
  fw::io::SiteSettings site;
  site.origin = {512040.25, 5401040.5, 421.0};  // a quarter metre: doubles keep it at UTM northings
  fw::io::CoordinateSystem& crs = site.crs.emplace();
  crs.wkt = "PROJCRS[\"WGS 84 / UTM zone 32N\",BASEGEOGCRS[\"WGS 84\"]]";  // kept as text, whatever it says
  crs.epsg = 32632;
  return site;
}

fw::io::WindFrame small_frame() {
  fw::io::WindFrame frame;
  frame.dims = {2, 2, 2};
  frame.h = 1.0;
  frame.velocity.assign(3 * frame.cell_count(), 1.0f);
  return frame;
}

}  // namespace

TEST_CASE("SiteVtk: a wind frame with a site reads back its origin, EPSG code and WKT, and one without none",
          "[io]") {
  const fw::test::TempDir dir("fw_site_vtk");
  const fw::io::SiteSettings site = utm_site();
  fw::io::WindFrame frame = small_frame();
  frame.site = &site;
  fw::io::write_wind_vti(dir.path() + "/site.vti", frame, {"speed"});
  frame.site = nullptr;
  fw::io::write_wind_vti(dir.path() + "/plain.vti", frame, {"speed"});

  auto field_data = [&](const std::string& name) {
    auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
    reader->SetFileName((dir.path() + "/" + name).c_str());
    reader->Update();
    return fw::io::read_site_field_data(*reader->GetOutput()->GetFieldData());
  };
  const auto back = field_data("site.vti");
  REQUIRE(back.has_value());
  CHECK(back->origin == site.origin);
  REQUIRE(back->crs.has_value());
  CHECK(back->crs->epsg == 32632);
  CHECK(back->crs->wkt == site.crs->wkt);
  CHECK_FALSE(field_data("plain.vti").has_value());
}

TEST_CASE("SiteVtk: a trees frame carries the site and each tree's inventory id by tree_id", "[io]") {
  const fw::test::TempDir dir("fw_site_vtk");
  fw::io::TreesFrame::Tree tree;
  tree.rest.resize(2, 3);
  tree.rest << 0, 0, 0, 0, 0, 1;
  tree.radius = {0.1, 0.05};
  tree.parent = {-1, 0};
  std::vector<fw::io::TreesFrame::Tree> trees{tree, tree};
  trees[1].tree_id = 1;
  const fw::io::TreesFieldData field_data{utm_site(), {"T0001", "plot 3, tree 7"}};
  fw::io::TreesVtp forest(trees, false, field_data);
  forest.write(dir.path() + "/trees.vtp", 0.0, {});
  auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  reader->SetFileName((dir.path() + "/trees.vtp").c_str());
  reader->Update();
  vtkFieldData& data = *reader->GetOutput()->GetFieldData();
  const auto site = fw::io::read_site_field_data(data);
  REQUIRE(site.has_value());
  CHECK(site->origin == utm_site().origin);
  auto* ids = vtkStringArray::SafeDownCast(data.GetAbstractArray("inventory_id"));
  REQUIRE(ids != nullptr);
  REQUIRE(ids->GetNumberOfValues() == 2);
  CHECK(ids->GetValue(0) == "T0001");
  CHECK(ids->GetValue(1) == "plot 3, tree 7");
}
